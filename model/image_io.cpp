#include "model/image_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "model/depth_format.hpp"
#include "model/errors.hpp"
#include "model/file_read.hpp"
#include "model/image_codec.hpp"

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

// The test-only write fault: with RASTERCMP_TEST_WRITE_FAULT=N, the N-th file this process writes
// through the atomic writers below (counting from 1) and every later one fail as on a full disk
// (ENOSPC), nothing left under the file's name or its temporary one. A full disk made with a
// file-size limit (ulimit -f, as tests/test_cli_children.cpp makes it) also stops lavapipe from
// Mesa 25 on, which backs device memory with memory files the limit applies to, so
// tests/test_cli_capture.cpp, whose command renders on lavapipe, fills the disk this way.
void fail_if_disk_full_for_test(const std::string& path) {
  static const long fault_from = [] {
    const char* value = std::getenv("RASTERCMP_TEST_WRITE_FAULT");
    return value != nullptr ? std::strtol(value, nullptr, 10) : 0L;
  }();
  static std::atomic<long> written{0};
  if (fault_from > 0 && ++written >= fault_from)
    throw InputError(path, "", std::string("could not write the file: ") + std::strerror(ENOSPC) +
                                   " (RASTERCMP_TEST_WRITE_FAULT)");
}

void write_image_atomic(const std::string& path, const ImageView& image) {
  fail_if_disk_full_for_test(path);
  const ImageCodec& codec = image_codec();
  const std::string tmp = temp_name_for(path);
  // Renamed only when every step, the close (the last flush) included, succeeded.
  const std::string why = codec.write(tmp, path, image);
  if (!why.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path, "", "could not write the image: " + why);
  }
  commit_temp(tmp, path);
}

PixelBuffer read_uint_image(const std::string& path, uint32_t& width, uint32_t& height, uint32_t& channels) {
  ImageU32 image;
  const std::string why = image_codec().read_u32(path, image);
  if (!why.empty()) throw InputError(path, "", "expected a readable image: " + why);
  width = image.width;
  height = image.height;
  channels = image.channels;
  return PixelBuffer(image.pixels.begin(), image.pixels.end());
}

// render.json "limits"; every field is optional and keeps its DeviceLimits default when absent.
DeviceLimits read_limits(const nlohmann::json& j, const std::string& file) {
  DeviceLimits l;
  if (!j.is_object()) throw InputError(file, "$.limits", "an object");
  try {
    l.sub_pixel_precision_bits = j.value("subPixelPrecisionBits", l.sub_pixel_precision_bits);
    l.viewport_sub_pixel_bits = j.value("viewportSubPixelBits", l.viewport_sub_pixel_bits);
    l.strict_lines = j.value("strictLines", l.strict_lines);
    l.standard_sample_locations = j.value("standardSampleLocations", l.standard_sample_locations);
    if (j.contains("lineWidthRange")) {
      const auto& range = j.at("lineWidthRange");
      if (!range.is_array() || range.size() != 2) throw InputError(file, "$.limits.lineWidthRange", "[min, max]");
      l.line_width_min = range[0].get<float>();
      l.line_width_max = range[1].get<float>();
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(file, "$.limits", std::string("device limits of the right types: ") + e.what());
  }
  if (l.sub_pixel_precision_bits == 0) throw InputError(file, "$.limits.subPixelPrecisionBits", "a value above 0");
  return l;
}

// "NAME (DRIVER)", as render.json's "device" reads when it has no "device_name" (older captures).
void split_device(const std::string& device, std::string& name, std::string& driver) {
  const size_t open = device.rfind(" (");
  if (!device.empty() && device.back() == ')' && open != std::string::npos) {
    name = device.substr(0, open);
    driver = device.substr(open + 2, device.size() - open - 3);
  } else {
    name = device;
    driver.clear();
  }
}

}  // namespace

void ensure_output_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) throw InputError(dir, "", "expected a folder that can be created: " + ec.message());
  if (access(dir.c_str(), W_OK) != 0) throw InputError(dir, "", "expected a writable folder");
}

namespace {

// Writes `text` to the temporary name of `path`; throws InputError naming `path` (nothing left).
void write_temp_text(const std::string& tmp, const std::string& path, const std::string& text) {
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
}

}  // namespace

void write_text_file_atomic(const std::string& path, const std::string& text) {
  fail_if_disk_full_for_test(path);
  const std::string tmp = temp_name_for(path);
  write_temp_text(tmp, path, text);
  commit_temp(tmp, path);
}

void write_text_files_together(const std::vector<std::pair<std::string, std::string>>& files) {
  std::vector<std::string> temps;
  try {
    for (const auto& [path, text] : files) {
      temps.push_back(temp_name_for(path));
      write_temp_text(temps.back(), path, text);
    }
  } catch (...) {
    std::error_code ec;
    for (const std::string& tmp : temps) fs::remove(tmp, ec);
    throw;
  }
  for (size_t i = 0; i < files.size(); ++i) commit_temp(temps[i], files[i].first);
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
  const uint32_t w = r.width, h = r.height, s = r.samples;
  write_image_atomic((fs::path(dir) / "owner.tif").string(), {w, h, s, PixelType::UInt32, r.owner.data(), true});

  // People see sample 0 of each pixel.
  std::vector<unsigned char> rgb(size_t(w) * h * 3);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) owner_false_colour(r.owner[r.index(x, y, 0)], &rgb[(size_t(y) * w + x) * 3]);
  write_image_atomic((fs::path(dir) / "owner.png").string(), {w, h, 3, PixelType::UInt8, rgb.data(), false});

  if (r.has_depth()) {
    write_image_atomic((fs::path(dir) / "depth_raw.tif").string(),
                       {w, h, s, PixelType::UInt32, r.depth_raw.data(), true});
    std::vector<float> depth(r.depth_raw.size());
    for (size_t i = 0; i < depth.size(); ++i) depth[i] = float(depth_raw_to_value(r.depth_format, r.depth_raw[i]));
    write_image_atomic((fs::path(dir) / "depth.exr").string(), {w, h, s, PixelType::Float, depth.data(), true});
  }

  nlohmann::ordered_json meta = {
      {"backend", r.backend},
      {"device", r.device},
      {"fma", r.fma},
      {"width", r.width},
      {"height", r.height},
      {"samples", r.samples},
      {"depth_format", to_string(r.depth_format)},
      {"depth", r.has_depth()},
  };
  if (!r.device_name.empty()) {
    meta["device_name"] = r.device_name;
    meta["driver"] = r.driver;
  }
  if (r.limits) {
    meta["limits"] = {
        {"subPixelPrecisionBits", r.limits->sub_pixel_precision_bits},
        {"viewportSubPixelBits", r.limits->viewport_sub_pixel_bits},
        {"strictLines", r.limits->strict_lines},
        {"standardSampleLocations", r.limits->standard_sample_locations},
        {"lineWidthRange", {r.limits->line_width_min, r.limits->line_width_max}},
    };
  }
  write_text_file_atomic((fs::path(dir) / "render.json").string(), meta.dump(2) + "\n");
}

namespace {

// render.json alone; `depth` and the stated size come back apart (0: not stated).
// render.json holds a few fields.
constexpr uint64_t kMaxRenderJsonBytes = uint64_t(1) << 20;

// The sample counts a render may record (Vulkan's VkSampleCountFlagBits reach 64).
constexpr uint32_t kMaxRenderSamples = 64;

// A size in render.json: absent is 0 (the images then disagree with the scene); a negative or
// fractional number, or one past `max`, is refused rather than wrapped to a huge unsigned value.
uint32_t size_field(const nlohmann::json& meta, const char* key, const std::string& meta_path, uint32_t max) {
  if (!meta.contains(key)) return 0;
  const nlohmann::json& v = meta.at(key);
  if (!v.is_number_unsigned() || v.get<uint64_t>() > max)
    throw InputError(meta_path, std::string("$.") + key,
                     "expected an integer from 0 to " + std::to_string(max) + ", found " + v.dump());
  return uint32_t(v.get<uint64_t>());
}

// How large an image file of w x h pixels of `samples` 32-bit channels may be: the raw pixels
// twice over (TIFF's headers and strips, or a compression that does not pay) and 1 MiB. Without a
// stated size (older outputs), a framebuffer of 4096 x 4096 x 4.
uint64_t image_file_cap(uint32_t w, uint32_t h, uint32_t samples) {
  if (w == 0 || h == 0 || samples == 0) w = h = 4096, samples = 4;
  return 2 * uint64_t(w) * h * samples * 4 + (uint64_t(1) << 20);
}

RenderResult read_render_json(const std::string& dir, bool& depth, uint32_t& width, uint32_t& height,
                              uint32_t& samples) {
  const std::string meta_path = (fs::path(dir) / "render.json").string();
  if (!fs::exists(meta_path)) throw InputError(meta_path, "", "expected render.json (rastercmp render or capture)");
  const std::string text = read_bounded_file(meta_path, kMaxRenderJsonBytes, "render.json");
  nlohmann::json meta;
  try {
    meta = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(meta_path, "", std::string("expected valid JSON: ") + e.what());
  }
  RenderResult r;
  std::string fmt_name;
  try {
    if (!meta.is_object()) throw InputError(meta_path, "", "a JSON object");
    r.backend = meta.value("backend", "");
    r.device = meta.value("device", "");
    r.fma = meta.value("fma", false);
    fmt_name = meta.value("depth_format", "none");
    depth = meta.value("depth", false);
    width = size_field(meta, "width", meta_path, kMaxFramebufferSide);
    height = size_field(meta, "height", meta_path, kMaxFramebufferSide);
    samples = size_field(meta, "samples", meta_path, kMaxRenderSamples);
    if (meta.contains("device_name")) {
      r.device_name = meta.at("device_name").get<std::string>();
      r.driver = meta.value("driver", "");
    } else if (r.backend == "vulkan") {
      split_device(r.device, r.device_name, r.driver);
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(meta_path, "", std::string("expected fields of the right types: ") + e.what());
  }
  if (meta.contains("limits")) r.limits = read_limits(meta.at("limits"), meta_path);
  bool known_format = false;
  for (DepthFormat f : kAllDepthFormats)
    if (fmt_name == to_string(f)) {
      r.depth_format = f;
      known_format = true;
    }
  if (!known_format) throw InputError(meta_path, "$.depth_format", "a known depth format, not \"" + fmt_name + "\"");
  return r;
}

}  // namespace

RenderResult read_render_info(const std::string& dir) {
  bool depth = false;
  uint32_t width = 0, height = 0, samples = 0;
  return read_render_json(dir, depth, width, height, samples);
}

RenderResult read_render_outputs(const std::string& dir) {
  bool depth = false;
  uint32_t width = 0, height = 0, samples = 0;
  RenderResult r = read_render_json(dir, depth, width, height, samples);
  uint32_t c = 0;
  const std::string owner_path = (fs::path(dir) / "owner.tif").string();
  check_bounded_file(owner_path, image_file_cap(width, height, samples),
                     "an owner image of the size render.json states");
  r.owner = read_uint_image(owner_path, r.width, r.height, c);
  r.samples = c;
  // Older outputs may lack the size; when render.json states it, the image must agree.
  if ((width != 0 && width != r.width) || (height != 0 && height != r.height) || (samples != 0 && samples != c))
    throw InputError(owner_path, "",
                     fmt::format("an image of {}x{} with {} sample(s) as render.json states, not {}x{} with {}", width,
                                 height, samples, r.width, r.height, c));
  if (depth) {
    uint32_t w2 = 0, h2 = 0, c2 = 0;
    const std::string depth_path = (fs::path(dir) / "depth_raw.tif").string();
    check_bounded_file(depth_path, image_file_cap(r.width, r.height, r.samples),
                       "a depth image of the owner image's size");
    r.depth_raw = read_uint_image(depth_path, w2, h2, c2);
    if (w2 != r.width || h2 != r.height || c2 != r.samples)
      throw InputError(depth_path, "",
                       fmt::format("an image of the owner image's size, {}x{} with {} sample(s), not {}x{} with {}",
                                   r.width, r.height, r.samples, w2, h2, c2));
  }
  return r;
}

}  // namespace rastercmp
