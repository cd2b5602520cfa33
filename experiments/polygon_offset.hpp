// `rastercmp sweep polygon-offset`: the wrong-surface and flip (z-fighting) fractions of a decal
// over its base on both backends, against slope factor, constant factor, clamp, depth format,
// far/near ratio and viewing angle; r per depth format as the driver writes it. Output folder:
// polygon_offset.csv (one row per point, appended), polygon_offset.json, charts, index.html.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "experiments/csv_log.hpp"
#include "experiments/depth_r.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

inline constexpr const char* kPolygonOffsetCsv = "polygon_offset.csv";

// One sweep point. Points of one series differ only along the series' axis, in order.
struct OffsetPoint {
  std::string experiment;  // far_near | constant | slope | clamp | angle | identical
  PairParams params;
};
using OffsetSeries = std::vector<OffsetPoint>;

std::vector<OffsetSeries> polygon_offset_plan(bool quick);
std::vector<std::string> polygon_offset_header();

// Runs the sweep (CSV), measures r, writes JSON, charts and the page. Throws EnvironmentError
// without Vulkan or gnuplot.
void run_polygon_offset_sweep(const SweepOptions& options);

// Charts and index.html from the CSV and the r measurements (polygon_offset_charts.cpp).
void write_polygon_offset_charts(const std::string& dir, const std::vector<DepthRMeasure>& r);

// depth_r.json: per format the measured r on each backend, the spec bound, and lavapipe's r
// (docs/lavapipe-rules.md §4.3) as `predicted`, also divided by the bound.
std::string r_json(const std::vector<DepthRMeasure>& measures);

// The identical-vertex control (experiment "identical"): a triangle drawn twice with the same
// vertices, the second with constant offset `constant` r towards the eye under compare op Less.
struct IdenticalControl {
  std::string format;
  double angle_deg = 0, constant = 0, wrong_cpu = NAN, wrong_vk = NAN;
  bool cpu_vk_agree = false;
  bool as_expected = false;  // constant 0: the second draw loses every pixel; constant 1: it wins every pixel
};
std::vector<IdenticalControl> identical_controls(const CsvTable& table);
// polygon_offset.json: {"identical_vertex_control": [...]} from the CSV.
std::string identical_control_json(const CsvTable& table);

// The depth_r chart's data: three blocks (measured CPU, measured Vulkan, predicted), rows
// (format index, format, r / spec bound).
std::vector<DataBlock> depth_r_blocks(const std::vector<DepthRMeasure>& measures);

}  // namespace rastercmp::experiments
