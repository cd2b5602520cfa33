#include "model/image_codec.hpp"

#include <dlfcn.h>

#include <filesystem>

#include "model/errors.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

// lib/ beside the running program's folder, then the program's own folder.
std::vector<fs::path> module_candidates() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {kImageCodecFile};
  return {exe.parent_path().parent_path() / "lib" / kImageCodecFile, exe.parent_path() / kImageCodecFile};
}

const ImageCodec* open_codec() {
  std::string tried;
  for (const fs::path& path : module_candidates()) {
    // Never closed: the codec serves the whole process.
    void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!module) {
      tried += "\n  " + path.string() + ": " + dlerror();
      continue;
    }
    using Entry = const ImageCodec* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(module, kImageCodecEntry));
    const ImageCodec* codec = entry ? entry() : nullptr;
    if (codec && codec->abi == kImageCodecAbi) return codec;
    tried += "\n  " + path.string() + ": not this build's image codec";
  }
  throw EnvironmentError("cannot open the image codec module (OpenImageIO; built with rastercmp, install it with "
                         "the executable):" + tried);
}

}  // namespace

const ImageCodec& image_codec() {
  static const ImageCodec* const codec = open_codec();
  return *codec;
}

}  // namespace rastercmp
