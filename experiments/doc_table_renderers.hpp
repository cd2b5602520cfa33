// The markdown tables each experiment command writes beside its other outputs (OUT/tables/NAME.md,
// experiments/doc_tables.hpp), rendered from the JSON text the command writes: one function per
// command, one table per name. docs/experiments.md embeds them by name.
#pragma once

#include <string>

namespace rastercmp::experiments {

// sweep polygon-offset: depth-r (depth_r.json), identical-vertex (polygon_offset.json).
void write_depth_r_tables(const std::string& dir, const std::string& depth_r_json);
void write_polygon_offset_tables(const std::string& dir, const std::string& polygon_offset_json);
// sweep zfight: zfight-run, zfight-series.
void write_zfight_tables(const std::string& dir, const std::string& zfight_json);
// chart speed-accuracy: speed-accuracy-run, speed-accuracy-triangles, speed-accuracy-lines (one per set).
void write_speed_accuracy_tables(const std::string& dir, const std::string& speed_accuracy_json);
// sweep stability: stability-fight-onset, stability-boundaries, stability-predictions,
// stability-expectations.
void write_stability_tables(const std::string& dir, const std::string& stability_json);
// chart scene-needs: scene-needs-suite, skip-savings, skip-savings-run.
void write_scene_needs_tables(const std::string& dir, const std::string& scene_needs_json);
// chart depth-precision: depth-precision.
void write_depth_precision_tables(const std::string& dir, const std::string& depth_precision_json);
// chart resolution: resolution.
void write_resolution_tables(const std::string& dir, const std::string& resolution_json);
// chart summary: summary-families.
void write_summary_tables(const std::string& dir, const std::string& summary_json);

// A value as the tables print it: "—" for null or NaN, integers from 1,000 on with thousands
// separators, else 3 significant digits.
std::string table_value(double value);

}  // namespace rastercmp::experiments
