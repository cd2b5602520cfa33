// Image files through OpenImageIO, opened on first use. libOpenImageIO pulls in about 250 shared
// libraries (codecs, OpenCV, GDAL, ...) whose symbols are bound at load time: linked into the
// executable, that cost ~0.35 s of every process start, including `--help`, a rejected scene
// and every conformance worker. So the library lives in a module of its own
// (librastercmp_image_codec.so, model/image_codec_oiio.cpp), which this opens with dlopen the
// first time an image is written or read. The module sits in lib/ beside the executable's
// folder (build/lib for build/app, build/tests, ...; PREFIX/lib for an installed PREFIX/bin).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace rastercmp {

enum class PixelType : uint8_t { UInt8, UInt32, Float };

// Interleaved pixels, row 0 first; `channels` values per pixel.
struct ImageView {
  uint32_t width = 0, height = 0, channels = 0;
  PixelType type = PixelType::UInt8;
  const void* pixels = nullptr;
  bool zip = false;  // zip compression (TIFF, EXR)
};

struct ImageU32 {
  uint32_t width = 0, height = 0, channels = 0;
  std::vector<uint32_t> pixels;
};

// The module's entry points. Errors come back as text ("" = success); the caller turns them into
// InputError naming its file.
struct ImageCodec {
  uint32_t abi = 0;  // kImageCodecAbi
  // Writes `image` to `file` in the format `format_of`'s extension names, with a fixed DateTime
  // (same input, same bytes).
  std::string (*write)(const std::string& file, const std::string& format_of, const ImageView& image) = nullptr;
  // Reads every channel of `file` as uint32.
  std::string (*read_u32)(const std::string& file, ImageU32& image) = nullptr;
  // OpenImageIO's "inferno" colour map of `count` values in [0, 1]: 3 bytes each into `rgb`.
  std::string (*inferno)(const float* values, size_t count, uint8_t* rgb) = nullptr;
};

inline constexpr uint32_t kImageCodecAbi = 1;
inline constexpr const char* kImageCodecEntry = "rastercmp_image_codec";
inline constexpr const char* kImageCodecFile = "librastercmp_image_codec.so";

// The module's table, opened on the first call (thread-safe). Throws EnvironmentError naming the
// paths tried when the module is missing or does not load.
const ImageCodec& image_codec();

}  // namespace rastercmp
