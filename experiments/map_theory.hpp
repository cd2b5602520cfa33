// What theory says of each method map series (method_maps.hpp), beside what the sweep measured.
// Two kinds of theory:
//   a predicted boundary (failure_boundary.hpp BoundaryPrediction): one parameter value where the
//     series starts to fail, checked against the measured bracket; the depth and visibility maps,
//     and line_end_offset (method_map_prediction below);
//   a per-point expectation (MapExpectation): theory's outcome at every point of the series —
//     clean, differs, refused — and, where a model gives it, the number of samples whose coverage
//     differs; checked point by point (check_expectation). Every series of the fill, clip, line and
//     cull maps has one, so has the exact path on every map measured against lavapipe, and so have
//     the series of the depth and visibility maps that have no predicted boundary (depth_far_near's
//     perspective_correct and D32 reversed, visibility's bsp).
// stability.json records both beside the measured bracket; the map charts draw them.
#pragma once

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "experiments/csv_log.hpp"
#include "experiments/failure_boundary.hpp"

namespace rastercmp::experiments {

// line_end_offset, Bresenham lines, line=dda and line=bresenham: the smallest end offset at which
// the real line crosses half a pixel at a column between the ends, so that the pixel it passes
// nearest (whose diamond it crosses) is no longer the one the integer line through the end pixels
// picks: min over columns k of (round(y_k) + 0.5 - y_k) run / k, in sub-pixels.
// (failure_boundary.hpp predicted_boundary asks here.)
std::optional<BoundaryPrediction> method_map_prediction(const std::string& experiment, const std::string& case_name,
                                                        const std::string& method);

enum class Outcome { Clean, Differs, Refused, Either };  // Either: theory leaves it open (a tie, a last bit)
const char* to_string(Outcome outcome);

// What theory may look at besides the parameter: whether either side covers a sample there, and
// the two sample counts (value_cpu, value_vk), for expectations about a method's relation to the
// reference (differs wherever drawn; adds samples and never loses one).
struct PointFacts {
  double param = NAN;
  bool drawn = false;
  double method_samples = NAN, reference_samples = NAN;
};
struct PointTheory {
  Outcome outcome = Outcome::Clean;
  double coverage_mismatch = NAN;  // predicted count of samples whose owner differs; NaN: no count
};

struct MapExpectation {
  std::string expected;  // the theory, in words (stability.json "expected")
  std::string legend;    // a few words for the chart's key
  std::function<PointTheory(const PointFacts&)> at;
  double marked = NAN;   // a parameter value the chart marks dashed (cull: edge-on), NaN for none
  std::string marked_label;
};
std::optional<MapExpectation> method_map_expectation(const std::string& experiment, const std::string& case_name,
                                                     const std::string& method);

// One point of a series against its expectation. measured: Refused (not_supported), Differs
// (the map's measure above 0, or above the benign end's value for excess_mismatch) or Clean.
struct PointCheck {
  double param = NAN;
  PointTheory predicted;
  Outcome measured = Outcome::Clean;
  double measured_coverage_mismatch = NAN;
  bool agrees = false;  // outcomes equal (Either takes any) and counts equal where predicted
};
std::vector<PointCheck> check_expectation(const CsvTable& table, const FailureBoundary& b,
                                          const MapExpectation& expected);
bool expectation_holds(const CsvTable& table, const FailureBoundary& b, const MapExpectation& expected);

}  // namespace rastercmp::experiments
