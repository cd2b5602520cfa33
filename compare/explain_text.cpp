#include "compare/explain_text.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <filesystem>

#include "compare/case_run.hpp"
#include "compare/report.hpp"
#include "cpu_raster/classic/classic_explain.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/explain.hpp"
#include "model/image_io.hpp"

namespace rastercmp {
namespace {

std::string owner_text(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} primitive {} (id {:#010x})", owner_draw(owner), owner_primitive(owner), owner);
}

// The final value of a sample in a render: owner + raw depth (and its value).
std::string value_text(const RenderResult& r, size_t index) {
  std::string text = "owner " + owner_text(r.owner[index]);
  if (!r.has_depth()) return text + (r.depth_format == DepthFormat::None ? "" : ", no depth read back");
  const uint32_t raw = r.depth_raw[index];
  return text + fmt::format(", depth raw {:#x} = {:.9g}", raw, depth_raw_to_value(r.depth_format, raw));
}

// The two values named by their part in the case: the judged renderer (the Vulkan device, or a
// classic CPU method) and the reference (compare/report.hpp cpu_is_judged).
std::string tail_text(const RenderResult& expected, const RenderResult& actual, const std::string& cpu_method,
                      CompareProfile profile, uint32_t x, uint32_t y, uint32_t sample) {
  const size_t i = expected.index(x, y, sample);
  const bool cpu_judged = cpu_is_judged(cpu_method);
  const std::string cpu = cpu_judged ? fmt::format("CPU {} (judged):", cpu_method) : "CPU exact model (reference):";
  const std::string vulkan = cpu_judged ? "Vulkan device (reference):" : "Vulkan device (judged):";
  const size_t width = std::max(cpu.size(), vulkan.size()) + 1;
  // The diff names a coverage difference from the device's side (expected = CPU, actual = Vulkan);
  // here it is named from the judged renderer's side, so that the word and what follows it agree:
  // "missing" when the judged renderer lacks the fragment the reference has, "unexpected" when it
  // adds one the reference lacks (report.hpp judged_kind).
  std::string classification = describe_sample(expected, actual, profile, x, y, sample);
  const std::string judged = judged_kind(classification, cpu_judged);
  if (judged == "judged lacks") classification = "missing (the judged renderer lacks it)";
  if (judged == "judged adds") classification = "unexpected (the judged renderer adds it)";
  return fmt::format("{:<{}}{}\n{:<{}}{}\n{:<{}}{}\n", cpu, width, value_text(expected, i), vulkan, width,
                     value_text(actual, i), "classification:", width, classification);
}

// The owners an exactly computing device leaves at sample `index` besides the estimate's
// (RenderResult::owner_alternatives), in ascending order.
std::vector<uint32_t> alternatives_at(const RenderResult& expected, size_t index) {
  std::vector<uint32_t> out;
  for (const OwnerAlternative& a : expected.owner_alternatives)
    if (a.sample == index) out.push_back(a.owner);
  return out;
}

// Which simulated devices leave `owner` there: "a device with floor vertex rounding, top-left tie
// rule leaves it (and 2 other devices)", or the general reason where none is named.
std::string devices_text(const std::vector<ExactDeviceOwner>& devices, uint32_t owner, bool open) {
  if (open)
    return "the owner is open here: it may cover the pixel, and no primitive that certainly covers it certainly "
           "beats it in the depth test";
  std::vector<std::string> names;
  for (const ExactDeviceOwner& d : devices)
    if (d.owner == owner) names.push_back(d.device);
  if (names.empty()) return "an exactly computing device (docs/spec-profile.md, Owners) leaves it";
  const std::string more = names.size() > 1 ? fmt::format(" (and {} other devices)", names.size() - 1) : "";
  return "a device with " + names.front() + " leaves it" + more;
}

// The observed owner judged against the estimate's and the alternatives (compare/diff.hpp).
std::string observed_text(const RenderResult& expected, const RenderResult& actual, CompareProfile profile, size_t i,
                          const std::vector<ExactDeviceOwner>& devices, bool open) {
  const SampleClass c = classify_sample(expected, actual, profile, i);
  const std::string owner = owner_text(actual.owner[i]);
  if (c == SampleClass::AllowedOwner)
    return owner + ": an allowed alternative (Pass): " + devices_text(devices, actual.owner[i], open);
  if (c == SampleClass::WrongOwner)
    return owner +
           ": neither the estimate's nor an allowed alternative (wrong owner, QualityWarning: only "
           "arithmetic error leaves it there)";
  if (c == SampleClass::Correct && actual.owner[i] != kOwnerBackground) return owner + ": the estimate's";
  return owner + ": coverage, not the owner, is judged here (see classification)";
}

// Spec profile: the estimate's owner, the alternatives exact devices allow and what the judged
// render left (docs/spec-profile.md "Owners"); `open`: the pixel's owner is open
// (SpecPixelRules::owner_open).
std::string owners_text(const Scene& scene, const CpuOptions& cpu_options, const RenderResult& expected,
                        const RenderResult& actual, CompareProfile profile, uint32_t x, uint32_t y, uint32_t sample,
                        bool open) {
  const size_t i = expected.index(x, y, sample);
  const std::vector<uint32_t> alternatives = alternatives_at(expected, i);
  std::vector<ExactDeviceOwner> devices;
  if (!alternatives.empty() && !open) devices = exact_device_owners_at(scene, cpu_options, x, y, sample);
  std::string text =
      "spec owners (docs/spec-profile.md, Owners):\n  estimate:     " + owner_text(expected.owner[i]) + "\n";
  if (alternatives.empty())
    text +=
        "  alternatives: none (no exact device simulated here leaves another owner, and where the owner is open "
        "every other primitive is certainly beaten; Owners names what is not simulated)\n";
  for (size_t k = 0; k < alternatives.size(); ++k)
    text += fmt::format("  {:<14}{}: {}\n", k == 0 ? "alternatives:" : "", owner_text(alternatives[k]),
                        devices_text(devices, alternatives[k], open));
  return text + "  observed:     " + observed_text(expected, actual, profile, i, devices, open) + "\n";
}

// Spec profile: the sample's class, the limits it was judged with, and what each primitive near it
// may do there (docs/spec-profile.md), so that a driver developer can argue with a MustNot.
std::string class_text(const SpecPixelRules& rules, const CpuOptions& cpu_options, const RenderResult& expected,
                       uint32_t x, uint32_t y, uint32_t sample) {
  static constexpr std::array<const char*, 3> kClass = {"MustNot", "May", "Must"};
  const CoverageClass c = expected.coverage_class[expected.index(x, y, sample)];
  std::string text = fmt::format(
      "spec class (docs/spec-profile.md): {}\n  limits:       subPixelPrecisionBits {}, viewportSubPixelBits {} ({} "
      "other viewport representation(s) judged besides the scene's own), strictLines unknown (DEFAULT lines: rectangle "
      "or "
      "parallelogram), lineWidthGranularity unknown (the nearest supported width)\n",
      kClass[size_t(c)], cpu_options.sub_pixel_bits, cpu_options.viewport_sub_pixel_bits, rules.viewports);
  for (const SpecPixelRules::Primitive& p : rules.primitives)
    text += fmt::format("  {:<14}{} ({}): {}, gate {}\n", &p == &rules.primitives.front() ? "primitives:" : "",
                        owner_text(p.owner), p.line ? "line" : "triangle piece", p.coverage, p.gate);
  std::string why;
  if (!rules.in_scissor)
    why = "outside the scissor rectangle (\"Scissor Test\": coverage 0)";
  else if (rules.undefined)
    why = "a primitive has undefined coordinates: anything inside the scissor may be covered";
  else if (c == CoverageClass::MustNot)
    why = rules.primitives.empty()
              ? "no primitive reaches the pixel under any placement of its vertices"
              : "no primitive may cover it: each misses the pixel box under every placement of its vertices on the "
                "sub-pixel grid (triangles), misses the widest line region (lines), or certainly fails against the "
                "clear value or is culled (gate never)";
  else if (c == CoverageClass::Must)
    why =
        "a primitive covers it whatever the device chose (full, gate certain), or two triangles share an edge "
        "through it and exactly one of them covers it";
  else
    why = "some primitive may cover it (partial, or gate maybe), none certainly";
  if (rules.viewports > 0 && rules.in_scissor)
    why += "; the class holds for every viewport representation (the primitives above: the scene's own viewport)";
  text += "  why:          " + why + "\n";
  if (rules.owner_open) text += "  owner open:   " + rules.open_reason + " (cpu_raster/spec/open_owners.hpp)\n";
  return text;
}

std::string header_text(const Scene& scene, CompareProfile profile, uint32_t x, uint32_t y, uint32_t sample,
                        bool classic = false) {
  return fmt::format("{}: pixel ({}, {}) sample {}, {} profile\nCPU history ({}):\n", scene.name, x, y, sample,
                     to_string(profile),
                     classic ? "the classic methods' own decisions, then the exact path's at the same sample"
                             : "every primitive that reached the pixel, in submission order");
}

}  // namespace

std::string explain_sample_text(const Scene& scene, const CpuOptions& cpu_options, const RenderResult& expected,
                                const RenderResult& actual, CompareProfile profile, uint32_t x, uint32_t y,
                                uint32_t sample) {
  if (uses_classic_methods(cpu_options))  // the methods' own history: cpu_raster/classic/classic_explain.hpp
    return header_text(scene, profile, x, y, sample, true) + explain_classic_pixel(scene, cpu_options, x, y, sample) +
           tail_text(expected, actual, cpu_method_label(cpu_options), profile, x, y, sample);
  const std::vector<FragmentRecord> history = explain_pixel(scene, cpu_options, x, y, sample);
  std::string text = header_text(scene, profile, x, y, sample) + format_explanation(history) +
                     tail_text(expected, actual, cpu_method_label(cpu_options), profile, x, y, sample);
  if (profile != CompareProfile::Spec || expected.coverage_class.empty()) return text;
  const SpecPixelRules rules = spec_pixel_rules(scene, cpu_options, expected, x, y);
  return text + class_text(rules, cpu_options, expected, x, y, sample) +
         owners_text(scene, cpu_options, expected, actual, profile, x, y, sample, rules.owner_open);
}

std::vector<ExplainLink> write_case_explanations(const std::string& report_dir, const std::string& case_name,
                                                 const Scene& scene, const CpuOptions& cpu_options,
                                                 const CaseResult& result, CompareProfile profile) {
  std::vector<ExplainLink> links;
  if (!result.diff || !result.expected || !result.actual) return links;
  const auto& bad = result.diff->summary.first_bad;
  for (size_t k = 0; k < bad.size() && k < kMaxExplainsPerCase; ++k) {
    const SampleLocation at = bad[k].at;
    std::string text;
    try {
      text = explain_sample_text(scene, cpu_options, *result.expected, *result.actual, profile, at.x, at.y, at.sample);
    } catch (const std::exception& e) {  // the history is missing, the values still explain something
      text = header_text(scene, profile, at.x, at.y, at.sample) +
             fmt::format("  (no CPU history for this sample: {})\n", e.what()) +
             tail_text(*result.expected, *result.actual, cpu_method_label(cpu_options), profile, at.x, at.y, at.sample);
    }
    const std::string file = fmt::format("{}/explain_{}_{}_s{}.txt", case_folder(case_name), at.x, at.y, at.sample);
    ensure_output_dir((std::filesystem::path(report_dir) / case_folder(case_name)).string());
    write_text_file_atomic((std::filesystem::path(report_dir) / file).string(), text);
    links.push_back({at, file});
  }
  return links;
}

}  // namespace rastercmp
