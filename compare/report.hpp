// The HTML report: per case the CPU and Vulkan owner images (false colour), an error mask in the
// CTS colours, a depth-difference heatmap, the numbers and the first bad samples; a summary table
// that sorts and filters by status. Images through OpenImageIO, the page through kainjow
// mustache (compare/templates/report.html.mustache). Layout of a report folder:
//   index.html
//   cases/<case>/cpu.png vulkan.png mask.png depth.png explain_<x>_<y>_s<sample>.txt
#pragma once

#include <array>
#include <cstdint>
#include <string>
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

// A pixel's class for the mask: the worst of its samples
// (missing > unexpected > wrong owner > allowed > correct > background).
SampleClass pixel_class(const SceneDiff& diff, uint32_t x, uint32_t y);

// The case's folder below the report folder: "cases/" + the name with characters other than
// [A-Za-z0-9._-] replaced by '_'.
std::string case_folder(const std::string& case_name);

// Writes the PNGs a case has renders for; returns their paths relative to `report_dir`.
// Throws InputError when a file cannot be written.
CaseImages write_case_images(const std::string& report_dir, const std::string& case_name, const CaseResult& result);

// The page (pure: the same records give the same bytes). Throws std::runtime_error when the
// embedded template does not parse.
std::string render_report_html(const RunInfo& info, const std::vector<CaseRecord>& records);

// Writes report_dir/index.html atomically.
void write_report_html(const std::string& report_dir, const RunInfo& info, const std::vector<CaseRecord>& records);

}  // namespace rastercmp
