// `rastercmp explain` text for one sample, as RenderDoc's pixel history shows it: every
// primitive that reached the sample on the CPU path (cpu_raster/exact/explain.hpp, or with classic
// methods cpu_raster/classic/classic_explain.hpp), then the Vulkan
// value there (owner + raw depth) and a one-line classification (compare/diff.hpp
// describe_sample). The report writes these for the first bad samples of a case and links them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "compare/case_record.hpp"
#include "compare/case_result.hpp"
#include "cpu_raster/exact/cpu_options.hpp"

namespace rastercmp {

// Explanations written per case with bad samples (its first ones in scan order).
inline constexpr size_t kMaxExplainsPerCase = 3;

// Throws NotSupportedError when the CPU profile cannot trace the scene.
std::string explain_sample_text(const Scene& scene, const CpuOptions& cpu_options, const RenderResult& expected,
                                const RenderResult& actual, CompareProfile profile, uint32_t x, uint32_t y,
                                uint32_t sample);

// Writes cases/<case>/explain_<x>_<y>_s<sample>.txt below `report_dir` for the first bad samples
// of a compared case; returns the links (relative to `report_dir`). Nothing for a case without
// a diff or without bad samples.
std::vector<ExplainLink> write_case_explanations(const std::string& report_dir, const std::string& case_name,
                                                 const Scene& scene, const CpuOptions& cpu_options,
                                                 const CaseResult& result, CompareProfile profile);

}  // namespace rastercmp
