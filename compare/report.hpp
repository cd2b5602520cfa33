// The HTML report, for triage: an index (run verdict, counts, the case table failures first, a
// status legend) and a page per case as the CTS logs one case (status and message, the baseline's
// reason, the reference, judged and difference images, a depth heatmap with its colour bar, the
// numbers, the first bad samples with a link to the full list, paginated, the explanations of the
// first bad samples and the scene source). In each case one renderer is judged against the other:
// the Vulkan device against the exact CPU model, or a classic CPU method (cpu_method other than
// "exact") against the Vulkan device. Images through OpenImageIO, pages through kainjow mustache
// (compare/templates/). Layout of a report folder:
//   index.html style.css
//   cases/<case>/index.html cpu.png vulkan.png mask.png depth.png bad-samples-<n>.html
//                explain_<x>_<y>_s<sample>.txt
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/case_result.hpp"
#include "compare/run_info.hpp"

namespace rastercmp {

// Error-mask colours (tcuRasterizationVerifier; wrong owner has no CTS colour: orange).
using Rgb = std::array<uint8_t, 3>;
inline constexpr Rgb kMaskMissing{255, 0, 255};
inline constexpr Rgb kMaskUnexpected{255, 0, 0};
inline constexpr Rgb kMaskWrongOwner{255, 128, 0};
inline constexpr Rgb kMaskAllowed{255, 255, 0};
inline constexpr Rgb kMaskCorrect{30, 30, 30};
inline constexpr Rgb kMaskBackground{0, 0, 0};

Rgb mask_colour(SampleClass c);

// Whether the CPU side is the one judged: a classic method is judged against the Vulkan device,
// the exact model is the reference the device is judged against.
bool cpu_is_judged(std::string_view cpu_method);

// A diff class seen from the judged renderer: when the CPU is judged, "missing" (the CPU covers,
// the device does not) is a sample the judged renderer adds, and "unexpected" one it lacks.
SampleClass judged_class(SampleClass c, bool cpu_judged);
// "missing" / "unexpected" of a BadSample::kind swapped the same way; other kinds unchanged.
std::string judged_kind(const std::string& kind, bool cpu_judged);

// A number as the report prints it: six significant digits.
std::string report_number(double v);

// How a runner status looks in the report: one row per status name, so a new status is one line.
struct StatusStyle {
  std::string_view key;  // the status name, or its part before '(' ("UnexpectedImprovement(Pass)")
  int group;             // case table order: 0 failing, 1 warning, 2 expected failure or flake, 3 pass, 4 not run here
  std::string_view background, colour;  // CSS colours
  std::string_view meaning;
};
std::span<const StatusStyle> status_styles();
// The row of `status`; a status the table does not know takes the "Other" row. The group of a
// case that fails the run is 0 whatever its status.
const StatusStyle& status_style(std::string_view status);
int status_group(const CaseRecord& record);
// The records in the case table's order: by status_group, then by name.
std::vector<const CaseRecord*> triage_order(const std::vector<CaseRecord>& records);

// A pixel's class for the mask: the worst of its samples
// (missing > unexpected > wrong owner > allowed > correct > background).
SampleClass pixel_class(const SceneDiff& diff, uint32_t x, uint32_t y);

// The case's folder below the report folder: "cases/" + the name with characters other than
// [A-Za-z0-9._-] replaced by '_'.
std::string case_folder(const std::string& case_name);

// Bad samples per page of a case's full list, and the page's file name in the case folder (n from 1).
inline constexpr size_t kBadSamplesPerPage = 200;
std::string bad_samples_page(size_t n);
// The number of bad samples of a diff (coverage errors + depth mismatches) and of their pages.
uint64_t bad_sample_count(const DiffSummary& diff);
size_t bad_sample_pages(const DiffSummary& diff);

// Writes cases/<case>/bad-samples-<n>.html, every bad sample of the diff in scan order (nothing
// for a case without a diff or without bad samples). write_case_images calls it.
void write_bad_sample_pages(const std::string& report_dir, const std::string& case_name, const CaseResult& result);

// "linear-gradient(to right, ...)": the heatmap's colour map (inferno) as a CSS colour bar.
std::string depth_colour_bar_css();

// Writes the files a case has renders for: the PNGs (the depth heatmap only when some depth
// differs) and, for a diff with bad samples, every bad sample on bad_sample_pages() pages.
// Returns the images' paths relative to `report_dir`. Throws InputError when a file cannot be
// written.
CaseImages write_case_images(const std::string& report_dir, const std::string& case_name, const CaseResult& result);

// The index page (pure: the same records give the same bytes). Throws std::runtime_error when an
// embedded template does not parse.
std::string render_report_html(const RunInfo& info, const std::vector<CaseRecord>& records);
// A case's page. Reads the scene file (record.source) and the explanation files below
// `report_dir`; the same files give the same bytes.
std::string render_case_html(const std::string& report_dir, const RunInfo& info, const CaseRecord& record);

// Writes report_dir/index.html, style.css and every record's cases/<case>/index.html (each
// atomically, and a page only when its bytes change).
void write_report_html(const std::string& report_dir, const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
