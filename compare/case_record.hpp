// What a run keeps of each case after its renders are gone: the verdict, the diff numbers, the
// outcome against the expectations and the report files. Every output (compare --json,
// results.csv, failures.csv, junit.xml, summary.json, the HTML report) is written from these,
// and `merge` reads them back from summary.json + results.csv.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "compare/diff.hpp"
#include "compare/verdict.hpp"

namespace rastercmp {

// An explanation file written for one bad sample, relative to the report folder.
struct ExplainLink {
  SampleLocation at;
  std::string file;
  bool operator==(const ExplainLink&) const = default;
};

// Report images of a case, relative to the report folder; empty when not written.
struct CaseImages {
  std::string cpu, vulkan, mask, depth_heatmap;
  bool operator==(const CaseImages&) const = default;
};

struct CaseRecord {
  std::string name;
  std::string source;                // scene file
  std::string cpu_method = "exact";  // the CPU side's method overrides ("fill=scanline depth=bilinear") or "exact"
  uint32_t width = 0, height = 0;
  Verdict verdict = Verdict::InternalError;
  std::string message;
  std::optional<DiffSummary> diff;
  // Against the expectations (conformance); compare leaves expectation Pass and judges alone.
  std::string expectation = "Pass";  // the baseline's runner status for the case (compare/expectations.hpp)
  std::string expectation_reason;    // the baseline entry's comment (compare/expectations.hpp), "" when none
  std::string status;                // runner status, e.g. "Pass", "ExpectedFail", "UnexpectedImprovement(Pass)"
  bool fails_run = false;
  double duration_s = 0;  // written only to results.csv and junit.xml
  CaseImages images;
  std::vector<ExplainLink> explains;

  bool operator==(const CaseRecord&) const = default;
};

// The per-scene JSON object (compare --json, summary.json "cases"): scene, source, cpu_method, verdict,
// message, width, height, pixels, samples, depth_format, coverage_mismatches, missing,
// unexpected, wrong_owner, allowed, allowed_owner, covered_match, bad_pixels, depth_mismatches, depth_unit,
// max_depth_error (+_r), depth_p50 / depth_p95 (+_r), max_depth_at, first_bad; the diff fields
// are null when the scene was not compared. `with_outcome` adds expectation, expectation_reason,
// status, fails_run, images and explains. Durations are never written here (deterministic output).
nlohmann::ordered_json case_to_json(const CaseRecord& record, bool with_outcome);

// The inverse of case_to_json(record, true). Throws InputError(file, json_path, expected).
CaseRecord case_from_json(const nlohmann::json& value, const std::string& file, const std::string& path);

}  // namespace rastercmp
