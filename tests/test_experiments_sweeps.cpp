// The three experiment commands in --quick mode, end to end (lavapipe + CPU + gnuplot): the CSV's
// contents, not only its existence. Skips only without a Vulkan device.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "experiments/csv_log.hpp"
#include "experiments/method_maps.hpp"
#include "experiments/polygon_offset.hpp"
#include "experiments/speed_accuracy.hpp"
#include "experiments/stability.hpp"
#include "experiments/sweep_common.hpp"
#include "experiments/table_query.hpp"
#include "model/errors.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::experiments {
namespace {

namespace fs = std::filesystem;

std::string vulkan_missing_reason() {
  try {
    VulkanRenderer renderer(VkOptions{});
    return "";
  } catch (const EnvironmentError& e) {
    return e.what();
  }
}

#define SKIP_WITHOUT_VULKAN()                                            \
  do {                                                                   \
    const std::string reason = vulkan_missing_reason();                  \
    if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason; \
  } while (0)

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("rastercmp_test_experiments_" + name);
  fs::remove_all(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void expect_chart(const fs::path& dir, const std::string& name) {
  EXPECT_NE(read_text(dir / (name + ".svg")).find("<svg"), std::string::npos) << name;
  EXPECT_GT(fs::file_size(dir / (name + ".png")), 1000u) << name;
  EXPECT_NE(read_text(dir / "index.html").find(name + ".svg"), std::string::npos) << name;
}

double cell(const CsvTable& table, const Where& where, const std::string& column) {
  const std::vector<Row> rows = select_rows(table, where);
  EXPECT_EQ(rows.size(), 1u);
  return rows.empty() ? NAN : to_double(rows.front()[table.column(column)]);
}

TEST(ExperimentsSweeps, PolygonOffsetQuick) {
  SKIP_WITHOUT_VULKAN();
  const fs::path dir = fresh_dir("polygon_offset");
  run_polygon_offset_sweep({dir.string(), true, false});
  const CsvTable table = read_csv((dir / kPolygonOffsetCsv).string());
  size_t planned = 0;
  for (const OffsetSeries& series : polygon_offset_plan(true)) planned += series.size();
  ASSERT_EQ(table.rows.size(), planned);
  for (const Row& row : table.rows)
    EXPECT_EQ(row[table.column("cpu_vk_agree")], "true") << join_fields(row, row.size());

  // Without offset the coplanar pair fights on D16 at far/near 10^6; with enough offset it does not.
  const Where far_near{{"experiment", "far_near"}, {"scene", "coplanar"}, {"format", "d16_unorm"}};
  Where none = far_near, enough = far_near;
  none.insert(none.end(), {{"constant", "0"}, {"far_near", "1000000"}});
  enough.insert(enough.end(), {{"constant", "4"}, {"slope", "2"}, {"far_near", "10"}});
  EXPECT_GT(cell(table, none, "wrong_cpu"), 0.0);
  EXPECT_GT(cell(table, none, "wrong_vk"), 0.0);
  EXPECT_EQ(cell(table, enough, "wrong_cpu"), 0.0);
  EXPECT_EQ(cell(table, enough, "wrong_vk"), 0.0);

  // r from the driver's output: lavapipe's 2/(2^n-1) for UNORM until Mesa 25.1 (above the spec's
  // 2*2^-n), 1/(2^n-1) from 25.2 (lavapipe-rules §8.4); 2^-25 at z 0.375 for D32.
  const nlohmann::json r = nlohmann::json::parse(read_text(dir / "depth_r.json"));
  ASSERT_EQ(r.size(), 3u);
  const double units = installed_lavapipe_release().rules().has(LavapipeRule::UnormBiasHalfUnit) ? 1.0 : 2.0;
  EXPECT_EQ(r[0]["format"], "d16_unorm");
  EXPECT_NEAR(r[0]["r_vulkan"].get<double>(), units / 65535.0, 1e-12);
  EXPECT_NEAR(r[0]["r_cpu"].get<double>(), units / 65535.0, 1e-12);
  EXPECT_EQ(r[0]["raw_step_vulkan"].get<double>(), units);
  if (units == 2.0) {
    EXPECT_GT(r[0]["r_vulkan"].get<double>(), r[0]["spec_bound"].get<double>());
  }
  EXPECT_NEAR(r[1]["r_vulkan"].get<double>(), units / 16777215.0, 1e-15);
  EXPECT_EQ(r[1]["raw_step_vulkan"].get<double>(), units);
  EXPECT_EQ(r[2]["r_vulkan"].get<double>(), std::ldexp(1.0, -25));  // z 0.375: e = -2
  for (const auto& format : r) EXPECT_EQ(format["r_cpu"], format["r_vulkan"]) << format["format"];

  // The identical-vertex control: on every format, lavapipe and the exact path alike, the second
  // draw of the same triangle loses every pixel without offset and wins every pixel with 1 r.
  const std::vector<IdenticalControl> controls = identical_controls(table);
  EXPECT_EQ(controls.size(), 3u * 2 * 2);  // formats x angles (0, 60) x constants (0, 1)
  for (const IdenticalControl& c : controls) {
    EXPECT_TRUE(c.as_expected) << c.format << " angle " << c.angle_deg << " constant " << c.constant;
    EXPECT_EQ(c.wrong_vk, c.constant == 0 ? 1.0 : 0.0) << c.format << " angle " << c.angle_deg;
  }
  const nlohmann::json control_json = nlohmann::json::parse(read_text(dir / "polygon_offset.json"));
  EXPECT_EQ(control_json["identical_vertex_control"].size(), controls.size());
  EXPECT_NE(read_text(dir / "index.html").find("Control: one triangle drawn twice"), std::string::npos);

  for (const char* chart : {"zfight_far_near_coplanar", "zfight_far_near_house", "min_constant_vs_angle",
                            "min_slope_vs_angle", "clamp", "wrong_vs_angle", "depth_r"})
    expect_chart(dir, chart);
}

TEST(ExperimentsSweeps, PolygonOffsetResumeAfterInterruptionGivesTheSameCsv) {
  SKIP_WITHOUT_VULKAN();
  const fs::path dir = fresh_dir("polygon_offset_resume");
  run_polygon_offset_sweep({dir.string(), true, false});
  const std::string full = read_text(dir / kPolygonOffsetCsv);
  // Cut the file in the middle of a row, as a killed run would leave it.
  const std::string cut = full.substr(0, full.size() / 3 + 7);
  std::ofstream(dir / kPolygonOffsetCsv, std::ios::binary | std::ios::trunc) << cut;
  run_polygon_offset_sweep({dir.string(), true, true});
  // Points are deterministic and the plan's order is fixed: the resumed file is the same file.
  EXPECT_EQ(read_text(dir / kPolygonOffsetCsv), full);
}

TEST(ExperimentsSweeps, StabilityQuick) {
  SKIP_WITHOUT_VULKAN();
  const fs::path dir = fresh_dir("stability");
  run_stability_sweep({dir.string(), true, false});
  const CsvTable table = read_csv((dir / kStabilityCsv).string());
  ASSERT_EQ(table.rows.size(), stability_plan(true).size());
  const size_t agree = table.column("cpu_vk_agree");

  // The exact path stays exact up to the viewportBoundsRange limit.
  const std::vector<Row> far = select_rows(table, {{"experiment", "far_distance"}});
  ASSERT_FALSE(far.empty());
  EXPECT_EQ(to_double(far.back()[table.column("param_a")]), 32767.0);
  for (const Row& row : far) EXPECT_EQ(row[agree], "true") << join_fields(row, row.size());
  for (const Row& row : select_rows(table, {{"experiment", "sliver"}, {"method", "exact"}}))
    EXPECT_EQ(row[agree], "true") << join_fields(row, row.size());
  for (const Row& row : select_rows(table, {{"experiment", "fight_onset"}}))
    EXPECT_EQ(row[agree], "true") << join_fields(row, row.size());

  // D16 starts to fight where one depth step exceeds the depth difference of the two surfaces:
  // d(z) = f/(f-n) (1 - n/z), so delta_d ~ n dz / z^2 with dz = separation / cos(30 deg) and z up to
  // 50 + 12 sin(30 deg) = 56 (the decal's far edge). Below half that ratio nothing may fight; above twice it, it must.
  const double dz = 0.1 / std::cos(kOnsetAngleDeg * M_PI / 180.0), z = 56.0;
  const double predicted = 100.0 * dz * 65535.0 / (z * z);
  const size_t ratio = table.column("param_b"), cpu = table.column("value_cpu"), vk = table.column("value_vk");
  size_t below = 0, above = 0;
  for (const Row& row :
       select_rows(table, {{"experiment", "fight_onset"}, {"case", "d16_unorm"}, {"param_a", "0.1"}})) {
    const double r = to_double(row[ratio]);
    if (r < predicted / 2) {
      ++below;
      EXPECT_EQ(to_double(row[cpu]), 0.0) << "far/near " << r;
      EXPECT_EQ(to_double(row[vk]), 0.0) << "far/near " << r;
    } else if (r > predicted * 2) {
      ++above;
      EXPECT_GT(to_double(row[cpu]), 0.0) << "far/near " << r;
      EXPECT_GT(to_double(row[vk]), 0.0) << "far/near " << r;
    }
  }
  EXPECT_GT(below, 0u);
  EXPECT_GT(above, 0u);
  const double d16 = fight_onset_ratio(table, "d16_unorm", "0.1"),
               d24 = fight_onset_ratio(table, "x8_d24_unorm", "0.1");
  EXPECT_TRUE(std::isnan(d24) || d24 > d16) << "D24 should fight later than D16";

  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "stability.json"));
  EXPECT_EQ(summary["far_distance"]["exact"]["points"], far.size());
  // Every (case, separation) of fight_onset: its onset distribution over the jitter ensemble beside
  // the predicted onset; the four mappings of each format are there.
  EXPECT_EQ(summary["fight_onset"].size(), 3u * 4);
  for (const auto& onset : summary["fight_onset"]) {
    EXPECT_EQ(onset["jitters"].get<int>(), onset_jitters(true)) << onset["case"];
    EXPECT_TRUE(onset.contains("onset_median") && onset.contains("predicted") && onset.contains("measured_low"))
        << onset["case"];
  }
  for (const char* chart : {"fight_vs_far_near", "fight_onset_map", "sliver_map"}) expect_chart(dir, chart);
  // A limit experiment whose points all match lavapipe is a table on the page, not a chart.
  for (const char* chart : {"far_distance", "near_w", "non_finite"})
    if (fs::exists(dir / (std::string(chart) + ".svg"))) expect_chart(dir, chart);
    else EXPECT_FALSE(limit_zero_table(table, chart).size() < 2) << chart;

  // Method maps: the exact path equals lavapipe on every scene of every map, which is what lets
  // test_experiments_boundaries use it as the reference; each map has its chart and its boundaries.
  // Mesa 26.2's overflow arithmetic is refused (lavapipe-rules §8.7): such a point is not_supported.
  const bool refuses = installed_lavapipe_release().rules().has(LavapipeRule::RasterizerOverflowReworked);
  size_t map_rows = 0;
  for (const MapExperiment& e : method_map_experiments()) {
    for (const Row& row : select_rows(table, {{"experiment", std::string(e.name)}, {"method", "exact"}})) {
      EXPECT_TRUE(row[agree] == "true" || (refuses && row[agree] == "not_supported")) << join_fields(row, row.size());
      ++map_rows;
    }
    expect_chart(dir, "map_" + std::string(e.name));
  }
  EXPECT_GT(map_rows, 100u);
  bool painter_cyclic = false;
  for (const auto& b : summary["boundaries"])
    if (b["experiment"] == "visibility_cyclic" && b["method"] == "visibility=painter") {
      painter_cyclic = true;
      EXPECT_EQ(b["last_clean"].get<double>(), 0.05);  // as pinned by test_experiments_boundaries
      EXPECT_EQ(b["boundary"].get<double>(), 0.1);
    }
  EXPECT_TRUE(painter_cyclic);
}

TEST(ExperimentsSweeps, SpeedAccuracyQuick) {
  SKIP_WITHOUT_VULKAN();
  const fs::path dir = fresh_dir("speed_accuracy");
  run_speed_accuracy({dir.string(), true, false});
  const CsvTable table = read_csv((dir / kSpeedAccuracyCsv).string());
  const std::vector<Row> reference = select_rows(table, {{"method", "lavapipe"}});
  const size_t triangle_scenes = speed_accuracy_scenes(false).size(), line_scenes = speed_accuracy_scenes(true).size();
  ASSERT_EQ(reference.size(), triangle_scenes + line_scenes);
  size_t triangle_entries = 0, line_entries = 0;
  for (const MethodEntry& e : speed_accuracy_entries()) ++(e.lines ? line_entries : triangle_entries);
  ASSERT_EQ(table.rows.size(), (triangle_entries + 1) * triangle_scenes + (line_entries + 1) * line_scenes);
  for (const Row& row : table.rows) {
    const double median = to_double(row[table.column("seconds_per_frame")]);
    EXPECT_GT(median, 0.0);
    EXPECT_LE(to_double(row[table.column("seconds_ci_low")]), median);
    EXPECT_GE(to_double(row[table.column("seconds_ci_high")]), median);
  }
  // The exact path, its fast paths and every depth format reproduce lavapipe on the whole set.
  for (const Where& where :
       {Where{{"method", "exact"}}, Where{{"family", "fast path"}}, Where{{"family", "depth format"}}})
    for (const Row& row : select_rows(table, where)) {
      EXPECT_EQ(to_double(row[table.column("coverage_mismatch_pct")]), 0.0) << join_fields(row, row.size());
      EXPECT_EQ(to_double(row[table.column("depth_mismatch_pct")]), 0.0) << join_fields(row, row.size());
    }
  // DDA and Bresenham are 1-pixel lines of their own: they differ from Vulkan's line rules.
  for (const char* method : {"line=dda", "line=bresenham"})
    EXPECT_GT(to_double(select_rows(table, {{"method", method}}).at(0)[table.column("coverage_mismatch_pct")]), 0.0);
  const nlohmann::json summary = nlohmann::json::parse(read_text(dir / "speed_accuracy.json"));
  ASSERT_EQ(summary["sets"].size(), 2u);
  for (const auto& set : summary["sets"]) {
    EXPECT_GT(set["lavapipe"]["seconds_per_frame"].get<double>(), 0.0);
    EXPECT_FALSE(set["pareto_front_coverage"].empty());
    EXPECT_FALSE(set["family_fronts_coverage"].empty());
    for (const auto& m : set["methods"]) EXPECT_NEAR(m["ci_coverage"].get<double>(), 0.9375, 1e-12);  // n = 5
  }
  EXPECT_TRUE(summary["sets"][1]["family_fronts_coverage"].contains("line"));
  for (const char* chart : {"speed_accuracy_coverage", "speed_accuracy_depth", "speed_accuracy_lines_coverage",
                            "speed_accuracy_lines_depth"})
    expect_chart(dir, chart);
}

}  // namespace
}  // namespace rastercmp::experiments
