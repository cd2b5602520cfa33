#include "model/image_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>
#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "model/depth_format.hpp"
#include "model/errors.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

// A path in the same folder that is renamed over the target once complete.
std::string temp_name_for(const std::string& path) {
  const fs::path p(path);
  return (p.parent_path() / fmt::format(".{}.tmp{}{}", p.stem().string(), getpid(), p.extension().string())).string();
}

void commit_temp(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError(path, "", "could not write the file (rename failed)");
  }
}

void write_image_atomic(const std::string& path, OIIO::ImageSpec spec, const void* pixels) {
  // Same input, same bytes: OpenImageIO would stamp the current time (TIFF DateTime, EXR capDate).
  spec.attribute("DateTime", "1970:01:01 00:00:00");
  const std::string tmp = temp_name_for(path);
  auto out = OIIO::ImageOutput::create(path);  // format from the final extension
  // Renamed only when every step, the close (the last flush) included, succeeded.
  const bool written = out && out->open(tmp, spec) && out->write_image(spec.format, pixels);
  const bool closed = out && out->close();
  if (!written || !closed) {
    const std::string why = out ? out->geterror() : OIIO::geterror();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path, "", "could not write the image: " + (why.empty() ? std::string("write failed") : why));
  }
  commit_temp(tmp, path);
}

std::vector<uint32_t> read_uint_image(const std::string& path, uint32_t& width, uint32_t& height, uint32_t& channels) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(path, "", "expected a readable image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  width = spec.width;
  height = spec.height;
  channels = spec.nchannels;
  std::vector<uint32_t> data(size_t(width) * height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT32, data.data()))
    throw InputError(path, "", "could not read the image: " + in->geterror());
  return data;
}

}  // namespace

void ensure_output_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(dir, "", "expected a folder that can be created: " + ec.message());
  if (access(dir.c_str(), W_OK) != 0) throw InputError(dir, "", "expected a writable folder");
}

void write_text_file_atomic(const std::string& path, const std::string& text) {
  const std::string tmp = temp_name_for(path);
  // Plain write(2) and close(2), each checked: a full disk (ENOSPC, EFBIG, EIO) leaves no file
  // under the final name.
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw InputError(path, "", std::string("could not write the file: ") + std::strerror(errno));
  size_t done = 0;
  int error = 0;
  while (done < text.size() && error == 0) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0)
      done += size_t(n);
    else if (n < 0 && errno != EINTR)
      error = errno;
    else if (n == 0)
      error = EIO;
  }
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path, "", std::string("could not write the file: ") + std::strerror(error));
  }
  commit_temp(tmp, path);
}

void owner_false_colour(uint32_t owner, unsigned char rgb[3]) {
  if (owner == kOwnerBackground) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  // Hash the id (draws and neighbouring primitives get far-apart colours), keep it bright.
  uint32_t h = owner * 2654435761u;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  rgb[0] = static_cast<unsigned char>(64 + (h & 0xFF) * 191 / 255);
  rgb[1] = static_cast<unsigned char>(64 + ((h >> 8) & 0xFF) * 191 / 255);
  rgb[2] = static_cast<unsigned char>(64 + ((h >> 16) & 0xFF) * 191 / 255);
}

void write_render_outputs(const RenderResult& r, const std::string& dir) {
  ensure_output_dir(dir);
  const int w = int(r.width), h = int(r.height), s = int(r.samples);

  OIIO::ImageSpec owner_spec(w, h, s, OIIO::TypeDesc::UINT32);
  owner_spec.attribute("compression", "zip");
  write_image_atomic((fs::path(dir) / "owner.tif").string(), owner_spec, r.owner.data());

  // People see sample 0 of each pixel.
  std::vector<unsigned char> rgb(size_t(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) owner_false_colour(r.owner[r.index(x, y, 0)], &rgb[(size_t(y) * w + x) * 3]);
  write_image_atomic((fs::path(dir) / "owner.png").string(), OIIO::ImageSpec(w, h, 3, OIIO::TypeDesc::UINT8),
                     rgb.data());

  if (r.has_depth()) {
    OIIO::ImageSpec raw_spec(w, h, s, OIIO::TypeDesc::UINT32);
    raw_spec.attribute("compression", "zip");
    write_image_atomic((fs::path(dir) / "depth_raw.tif").string(), raw_spec, r.depth_raw.data());
    std::vector<float> depth(r.depth_raw.size());
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = float(depth_raw_to_value(r.depth_format, r.depth_raw[i]));
    OIIO::ImageSpec exr_spec(w, h, s, OIIO::TypeDesc::FLOAT);
    exr_spec.attribute("compression", "zip");
    write_image_atomic((fs::path(dir) / "depth.exr").string(), exr_spec, depth.data());
  }

  const nlohmann::ordered_json meta = {
      {"backend", r.backend},
      {"device", r.device},
      {"fma", r.fma},
      {"width", r.width},
      {"height", r.height},
      {"samples", r.samples},
      {"depth_format", to_string(r.depth_format)},
      {"depth", r.has_depth()},
  };
  write_text_file_atomic((fs::path(dir) / "render.json").string(), meta.dump(2) + "\n");
}

RenderResult read_render_outputs(const std::string& dir) {
  const std::string meta_path = (fs::path(dir) / "render.json").string();
  std::ifstream in(meta_path);
  if (!in) throw InputError(meta_path, "", "expected render.json from rastercmp render");
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(meta_path, "", std::string("expected valid JSON: ") + e.what());
  }
  RenderResult r;
  r.backend = meta.value("backend", "");
  r.device = meta.value("device", "");
  r.fma = meta.value("fma", false);
  const std::string fmt_name = meta.value("depth_format", "none");
  for (DepthFormat f : kAllDepthFormats)
    if (fmt_name == to_string(f)) r.depth_format = f;
  uint32_t c = 0;
  r.owner = read_uint_image((fs::path(dir) / "owner.tif").string(), r.width, r.height, c);
  r.samples = c;
  if (meta.value("depth", false)) {
    uint32_t w2 = 0, h2 = 0, c2 = 0;
    r.depth_raw = read_uint_image((fs::path(dir) / "depth_raw.tif").string(), w2, h2, c2);
  }
  return r;
}

}  // namespace rastercmp
