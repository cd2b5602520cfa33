// `rastercmp chart resolution`: how each classic method's error against the exact path grows with the
// framebuffer's size. The scene sets of `chart speed-accuracy` (speed_accuracy_scenes) are rendered
// at square sizes 64 .. 4096: their positions are clip coordinates, so the same geometry covers the
// larger frame (a 1-pixel line stays 1 pixel wide). Each method entry of speed_accuracy_entries()
// that swaps a stage of the scalar exact path is compared sample by sample with the exact path
// (CPU only: the exact path equals lavapipe bit for bit, held by the conformance tests).
//
// The rule: a method whose error lives where a decision near an edge or along a line differs (a
// sub-pixel rounding of fixed width: the fills, snapping, tie rules, the line rasterizers, the line
// clippers' depths along a line) differs on a number of samples proportional to the edge or line
// length, so its count grows as size^1 and its fraction (count / size^2) as size^-1. A method whose
// error lives inside every covered pixel (depth interpolation: each sample's depth rounds
// differently; visibility: whole surfaces in another order; clipping: the depth plane of each clipped
// piece; culling: whole triangles) differs on a number proportional to the area: size^2, fraction
// constant. The measured exponent is the least-squares slope of log count against log size over
// the sizes with a non-zero count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cpu_raster/cpu_raster.hpp"
#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

struct ResolutionMethod {
  std::string family, method;
  CpuOptions cpu;
  bool lines = false;          // the line scene set
  int predicted_exponent = 0;  // count ~ size^p: 1 edge or line, 2 area
};

// The scalar entries of speed_accuracy_entries() other than the exact path and the depth formats,
// each with its predicted exponent (from its family: fill, set-up, line and line clipping 1; the others 2).
std::vector<ResolutionMethod> resolution_methods();

// The speed-accuracy scene set at width = height = size.
std::vector<Scene> resolution_scenes(bool lines, uint32_t size);

struct ResolutionPoint {
  std::string family, method;
  uint32_t size = 0;
  size_t samples = 0, coverage = 0, depth = 0, either = 0;  // samples whose owner / raw depth / either differ
  bool refused = false;                                     // NotSupported on a scene of its set
  double fraction() const { return samples ? double(either) / double(samples) : 0.0; }
};

// Every method at every size, its set's scenes summed. Deterministic (scalar renders).
std::vector<ResolutionPoint> measure_resolution(const std::vector<ResolutionMethod>& methods,
                                                const std::vector<uint32_t>& sizes);

// Least-squares slope of log(count) on log(size) over the points with a count > 0; NaN with fewer
// than two such points.
double count_exponent(const std::vector<ResolutionPoint>& points);

// Measured exponent within this distance of the predicted one: the rule holds.
inline constexpr double kExponentTolerance = 0.35;

std::vector<uint32_t> resolution_sizes(bool quick);  // 64 .. 4096 (64 .. 512 with --quick)

void run_resolution_sweep(const SweepOptions& options);

}  // namespace rastercmp::experiments
