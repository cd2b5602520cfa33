// The report's per-case images (compare/report.hpp).
#include <fmt/core.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>

#include "compare/report.hpp"
#include "model/errors.hpp"
#include "model/image_codec.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace fs = std::filesystem;
namespace {

// 8-bit RGB, row 0 first.
struct RgbImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

// Written to a temporary name in the same folder, then renamed: a reader never sees half a PNG.
void write_png_atomic(const RgbImage& image, const fs::path& path) {
  const fs::path tmp = path.parent_path() / fmt::format(".{}.tmp{}.png", path.stem().string(), getpid());
  const std::string why =
      image_codec().write(tmp.string(), path.string(), {image.width, image.height, 3, PixelType::UInt8, image.rgb.data()});
  if (!why.empty()) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError(path.string(), "", "could not write the image: " + why);
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) throw InputError(path.string(), "", "could not write the image: " + ec.message());
}

// OpenImageIO's "inferno" colour map of values in [0, 1].
std::vector<uint8_t> inferno_rgb(const std::vector<float>& values) {
  std::vector<uint8_t> rgb(values.size() * 3);
  const std::string why = image_codec().inferno(values.data(), values.size(), rgb.data());
  if (!why.empty()) throw std::runtime_error(why);
  return rgb;
}

// Sample 0 of each pixel in the owners' false colours (model/image_io.hpp).
RgbImage owner_image(const RenderResult& r) {
  RgbImage image{r.width, r.height, std::vector<uint8_t>(size_t(r.width) * r.height * 3)};
  for (uint32_t y = 0; y < r.height; ++y)
    for (uint32_t x = 0; x < r.width; ++x)
      owner_false_colour(r.owner[r.index(x, y, 0)], &image.rgb[(size_t(y) * r.width + x) * 3]);
  return image;
}

// Missing / unexpected as the judged renderer sees them (judged_class).
RgbImage mask_image(const SceneDiff& diff, bool cpu_judged) {
  const DiffSummary& s = diff.summary;
  RgbImage image{s.width, s.height, std::vector<uint8_t>(size_t(s.width) * s.height * 3)};
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x) {
      const Rgb c = mask_colour(judged_class(pixel_class(diff, x, y), cpu_judged));
      std::copy(c.begin(), c.end(), image.rgb.begin() + std::ptrdiff_t((size_t(y) * s.width + x) * 3));
    }
  return image;
}

// |diff| in r, the largest of the pixel's samples, normalised to the case's maximum, through
// OIIO's "inferno" colour map (black = no difference).
RgbImage depth_heatmap(const SceneDiff& diff) {
  const DiffSummary& s = diff.summary;
  std::vector<float> level(size_t(s.width) * s.height, 0.0f);
  for (size_t p = 0; p < level.size(); ++p)
    for (uint32_t sample = 0; sample < s.samples; ++sample)
      level[p] = std::max(level[p], diff.depth_diff_r[p * s.samples + sample]);
  const float scale = level.empty() ? 0.0f : *std::max_element(level.begin(), level.end());
  if (scale > 0)
    for (float& v : level) v /= scale;
  return {s.width, s.height, inferno_rgb(level)};
}

// inferno at 0, 0.1, ..., 1 (the colour map the heatmap uses).
std::vector<Rgb> inferno_stops() {
  constexpr int kStops = 11;
  std::vector<float> ramp(kStops);
  for (int i = 0; i < kStops; ++i) ramp[size_t(i)] = float(i) / float(kStops - 1);
  const std::vector<uint8_t> rgb = inferno_rgb(ramp);
  std::vector<Rgb> stops;
  for (int i = 0; i < kStops; ++i)
    stops.push_back({rgb[size_t(i) * 3], rgb[size_t(i) * 3 + 1], rgb[size_t(i) * 3 + 2]});
  return stops;
}

int class_rank(SampleClass c) {
  switch (c) {
    case SampleClass::Missing: return 5;
    case SampleClass::Unexpected: return 4;
    case SampleClass::WrongOwner: return 3;
    case SampleClass::Allowed: return 2;
    case SampleClass::AllowedOwner: return 2;
    case SampleClass::Correct: return 1;
    case SampleClass::Background: return 0;
  }
  return 0;
}

}  // namespace

Rgb mask_colour(SampleClass c) {
  switch (c) {
    case SampleClass::Missing: return kMaskMissing;
    case SampleClass::Unexpected: return kMaskUnexpected;
    case SampleClass::WrongOwner: return kMaskWrongOwner;
    case SampleClass::Allowed: return kMaskAllowed;
    case SampleClass::AllowedOwner: return kMaskAllowed;
    case SampleClass::Correct: return kMaskCorrect;
    case SampleClass::Background: return kMaskBackground;
  }
  return kMaskBackground;
}

std::string depth_colour_bar_css() {
  static const std::string css = [] {
    const std::vector<Rgb> stops = inferno_stops();
    std::string text = "linear-gradient(to right";
    for (size_t i = 0; i < stops.size(); ++i)
      text += fmt::format(", rgb({},{},{}) {}%", stops[i][0], stops[i][1], stops[i][2], i * 100 / (stops.size() - 1));
    return text + ")";
  }();
  return css;
}

SampleClass pixel_class(const SceneDiff& diff, uint32_t x, uint32_t y) {
  const DiffSummary& s = diff.summary;
  SampleClass worst = SampleClass::Background;
  for (uint32_t sample = 0; sample < s.samples; ++sample) {
    const SampleClass c = diff.sample_class[(size_t(y) * s.width + x) * s.samples + sample];
    if (class_rank(c) > class_rank(worst)) worst = c;
  }
  return worst;
}

std::string case_folder(const std::string& case_name) {
  std::string folder = case_name;
  for (char& ch : folder) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ||
                      ch == '_' || ch == '-';
    if (!keep) ch = '_';
  }
  if (folder.empty() || folder == "." || folder == "..") folder = "_" + folder;
  return "cases/" + folder;
}

CaseImages write_case_images(const std::string& report_dir, const std::string& case_name, const CaseResult& result) {
  CaseImages images;
  if (!result.expected && !result.actual) return images;
  const std::string folder = case_folder(case_name);
  ensure_output_dir((fs::path(report_dir) / folder).string());
  auto write = [&](const RgbImage& image, const char* file, std::string& relative) {
    relative = folder + "/" + file;
    write_png_atomic(image, fs::path(report_dir) / relative);
  };
  if (result.expected) write(owner_image(*result.expected), "cpu.png", images.cpu);
  if (result.actual) write(owner_image(*result.actual), "vulkan.png", images.vulkan);
  if (result.diff) {
    write(mask_image(*result.diff, cpu_is_judged(result.cpu_method)), "mask.png", images.mask);
    if (!result.diff->depth_diff_r.empty() && result.diff->summary.depth.mismatches != 0)
      write(depth_heatmap(*result.diff), "depth.png", images.depth_heatmap);
    write_bad_sample_pages(report_dir, case_name, result);
  }
  return images;
}

}  // namespace rastercmp
