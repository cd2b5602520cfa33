// `rastercmp chart summary`: every measured boundary beside its prediction, in one chart. It reads
// the JSON of earlier runs (it renders nothing itself):
//   stability.json       (sweep stability)        each entry of "boundaries" with a "predicted":
//                        the bracket [measured_low, measured_high] against predicted
//   zfight.json          (sweep zfight)           each entry of "series": the onset bracket
//                        (measured_onset_above, measured_onset_at_most] against predicted_onset,
//                        with predicted_onset_interval as the prediction's own interval
//   depth_r.json         (sweep polygon-offset)   each format: r measured on the CPU and on Vulkan
//                        (r_cpu, r_vulkan) against predicted
//   depth_precision.json (chart depth-precision)  each series: measured / ideal bucket, min .. max
//   resolution.json      (chart resolution)       each method: measured against predicted exponent
// Every value is divided by its prediction, so 1 is agreement. Fields the reader does not use are
// ignored; a field it uses that is missing or of another type is an InputError naming the file and
// the field's JSON path.
#pragma once

#include <string>
#include <vector>

#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

struct SummaryRow {
  std::string source;  // the file it came from, e.g. "stability.json"
  std::string family;  // e.g. "depth", "pseudo-depth", "z-fighting (model)", "depth precision"
  std::string label;   // what the row is: case and method
  double low = 0, high = 0;                  // the measured bracket / prediction (low == high: one value)
  double predicted_low = 1, predicted_high = 1;  // the prediction's own interval / prediction (1, 1: a value)
  bool agrees = false;                       // the source's own verdict (predicted_in_bracket, agrees, ...)
};

inline constexpr const char* kSummaryInputs[] = {"stability.json", "zfight.json", "depth_r.json",
                                                 "depth_precision.json", "resolution.json"};

// The rows of one known file (its name picks the reader). Throws InputError naming the file and field.
std::vector<SummaryRow> read_summary_file(const std::string& path);

// Every known file in each folder, in kSummaryInputs order per folder. A folder that holds none of
// them, or does not exist, is an InputError naming it and the files looked for.
std::vector<SummaryRow> read_summary_inputs(const std::vector<std::string>& dirs);

// The folders `chart summary` reads without --from: the commands' default output folders that
// exist in the working directory.
std::vector<std::string> default_summary_dirs();

void run_summary(const SweepOptions& options, const std::vector<std::string>& from_dirs);

}  // namespace rastercmp::experiments
