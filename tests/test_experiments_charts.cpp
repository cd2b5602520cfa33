// The data behind the experiments' charts and JSON, without rendering: the scene-needs block has no
// header row, an all-zero limit experiment becomes a table, depth_r is plotted as r / bound, the
// symmetric log axis keeps real values, and a method map's JSON carries `predicted` beside its
// measured bracket.
#include <gtest/gtest.h>

#include <cmath>

#include "experiments/failure_boundary.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/polygon_offset.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/skip_savings.hpp"
#include "experiments/stability.hpp"

namespace rastercmp::experiments {
namespace {

CsvTable limit_table(const std::vector<std::string>& coverage) {
  CsvTable t;
  t.header = {"experiment", "case",           "method",         "param_a",     "param_b",
              "value_cpu",  "value_vk",       "coverage_mismatch", "depth_mismatch", "cpu_vk_agree"};
  const char* params[] = {"1", "0.001", "0", "-1e-06"};
  for (size_t i = 0; i < coverage.size(); ++i)
    t.rows.push_back({"near_w", "vertex", "exact", params[i], "0", "10", "10", coverage[i], "0", "true"});
  return t;
}

TEST(ExperimentsCharts, SuiteNeedsBlockHasNoHeaderRowAndEveryStage) {
  StageNeeds clipped;
  clipped.clipping = true;
  const DataBlock block = suite_needs_block({clipped, StageNeeds{}});
  ASSERT_EQ(block.rows.size(), pipeline_stages().size());
  EXPECT_EQ(block.rows.front(), (std::vector<std::string>{"clipping", "1", "1"}));
  EXPECT_EQ(block.rows.back()[0], "culling");
  for (const auto& row : block.rows) EXPECT_NE(row[1], "needs") << "a header row is read as data";
}

TEST(ExperimentsCharts, AllZeroLimitExperimentIsATable) {
  const CsvTable zeros = limit_table({"0", "0", "0", "0"});
  EXPECT_TRUE(only_zeros(limit_blocks(zeros, "near_w"), 2));
  const auto table = limit_zero_table(zeros, "near_w");
  ASSERT_EQ(table.size(), 5u);
  EXPECT_EQ(table[3][2], "0");
  EXPECT_EQ(table[4][2], "-1e-06");
  const CsvTable one = limit_table({"0", "3", "0", "0"});
  EXPECT_FALSE(only_zeros(limit_blocks(one, "near_w"), 2));
  EXPECT_FALSE(only_zeros({DataBlock{"nan only", {{"0", "x", "nan"}}}}, 2));
}

TEST(ExperimentsCharts, SymlogAxisPlacesZeroAndNegativesAtTheirValues) {
  const SymlogAxis axis({1, 0.001, 1e-20, 0, -1e-6});
  EXPECT_EQ(axis.position(0), 0.0);
  EXPECT_DOUBLE_EQ(axis.position(1e-20), 1.0);
  EXPECT_DOUBLE_EQ(axis.position(1), 21.0);
  EXPECT_DOUBLE_EQ(axis.position(0.001), 18.0);
  EXPECT_DOUBLE_EQ(axis.position(-1e-6), -15.0);
  // Uneven values keep uneven gaps: 1 -> 0.001 is three decades, 0.001 -> 1e-20 seventeen.
  const std::vector<DataBlock> blocks = limit_blocks(limit_table({"0", "1", "0", "0"}), "near_w");
  EXPECT_NE(axis.tics_command("x", {"0"}).find("'0' 0"), std::string::npos);
  EXPECT_EQ(blocks[0].rows[2][0], "0");
  EXPECT_NE(blocks[0].rows[0][0], "0");
}

TEST(ExperimentsCharts, DepthRSeriesIsROverBound) {
  DepthRMeasure d16;
  d16.format = DepthFormat::D16Unorm;
  d16.spec_bound = 2.0 / 65536;
  d16.lavapipe_formula = 2.0 / 65535;
  d16.r_cpu = d16.r_vk = 2.0 / 65535;
  const std::vector<DataBlock> blocks = depth_r_blocks({d16});
  ASSERT_EQ(blocks.size(), 3u);
  for (const DataBlock& b : blocks) EXPECT_NEAR(std::stod(b.rows[0][2]), 65536.0 / 65535, 1e-9) << b.title;
  EXPECT_GT(std::stod(blocks[0].rows[0][2]), 1.00001);
  const std::string json = r_json({d16});
  EXPECT_NE(json.find("\"predicted\""), std::string::npos);
  EXPECT_NE(json.find("\"predicted_over_spec_bound\""), std::string::npos);
}

TEST(ExperimentsCharts, MapJsonCarriesPredictedBesideTheMeasuredBracket) {
  FailureBoundary painter{"visibility_cyclic", "visibility", "three_bars", "visibility=painter", 0.09, 0.075, 11, 7, 0,
                          {}};
  const nlohmann::ordered_json j = boundary_json(painter);
  ASSERT_TRUE(j.contains("predicted"));
  EXPECT_NEAR(j["predicted"].get<double>(), 0.0808, 1e-4);
  EXPECT_EQ(j["measured_low"].get<double>(), 0.075);
  EXPECT_EQ(j["measured_high"].get<double>(), 0.09);
  EXPECT_TRUE(j["predicted_in_bracket"].get<bool>());
  FailureBoundary late = painter;
  late.last_clean = 0.09, late.boundary = 0.1;
  EXPECT_FALSE(boundary_json(late)["predicted_in_bracket"].get<bool>());
  // Descending sweep (pseudo-depth separations shrink): D16 far 750 predicts about 0.23.
  const auto pseudo = predicted_boundary("pseudo_depth", "d16_unorm", "depth=pseudo_depth_750");
  ASSERT_TRUE(pseudo.has_value());
  EXPECT_NEAR(pseudo->value, 0.23, 0.01);
  FailureBoundary series{"pseudo_depth", "depth", "d16_unorm", "depth=pseudo_depth_750", 0.178, 0.316, 32, 22, 0, {}};
  EXPECT_TRUE(check_bracket(series, pseudo->value).in_bracket);
  // D16 z-fighting onset 241 and the interpenetration depth 0.0531.
  EXPECT_NEAR(predicted_boundary("depth_far_near", "d16_unorm", "exact")->value, 241.3, 0.1);
  EXPECT_NEAR(predicted_boundary("visibility_interpenetration", "two_squares", "visibility=painter")->value, 0.053125,
              1e-9);
  EXPECT_FALSE(predicted_boundary("fill_fan", "fan", "exact").has_value());
  // A refused point is kept in the JSON with its parameter.
  FailureBoundary refused{"clip_near_w", "clip", "triangle", "clip=weiler_atherton", 0.1, 1, 12, 7, 1, {0.0}};
  EXPECT_EQ(boundary_json(refused)["refused_values"], nlohmann::ordered_json::array({0.0}));
  EXPECT_FALSE(boundary_json(refused).contains("predicted"));
}

// fight_onset over a jitter ensemble: one onset per jitter (a jitter that never fights is +inf),
// nearest-rank quartiles, and the grid ratio before the smallest onset as the bracket's low end.
TEST(ExperimentsCharts, OnsetDistributionOverTheJitterEnsemble) {
  CsvTable t{stability_header(), {}};
  const char* ratios[] = {"10", "100", "1000"};
  // jitter 0 fights from 100, jitter 1 from 1000, jitter 2 never, jitter 3 from 10.
  const int first_wrong[] = {1, 2, 3, 0};
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 3; ++k)
      t.rows.push_back({"fight_onset", "d16_unorm", "exact", "0.1", ratios[k], std::to_string(j),
                        k >= first_wrong[j] ? "0.5" : "0", "0", "0", "0", "true"});
  EXPECT_EQ(fight_onset_ratio(t, "d16_unorm", "0.1"), 100.0);
  EXPECT_TRUE(std::isnan(fight_onset_ratio(t, "d16_unorm", "0.1", "2")));
  const OnsetDistribution d = fight_onset_distribution(t, "d16_unorm", "0.1");
  ASSERT_EQ(d.onsets.size(), 4u);
  EXPECT_EQ(d.never, 1u);
  EXPECT_EQ(d.min, 10.0);
  EXPECT_EQ(d.median, 1000.0);  // sorted 10, 100, 1000, inf: rank (2 * 3 + 2) / 4 = 2
  EXPECT_TRUE(std::isinf(d.max));
  EXPECT_TRUE(std::isnan(d.before_min));  // the first grid value fights already
}

TEST(ExperimentsCharts, OnsetPredictionPerFormatAndMapping) {
  // D16 at separation 0.1: 100 (0.1 / cos 30) 65535 / 56^2 = 241, the same for every mapping
  // (UNORM steps are uniform); D32 reversed has none; D32 standard steps as 24 bits near 1.
  EXPECT_NEAR(predicted_onset("d16_unorm", 0.1)->value, 241.3, 0.1);
  EXPECT_NEAR(predicted_onset("d16_unorm_reversed_z_float", 0.1)->value, 241.3, 0.1);
  EXPECT_NEAR(predicted_onset("x8_d24_unorm_double_z", 1)->value, 617751, 1);
  EXPECT_EQ(predicted_onset("d32_sfloat", 0.1)->value, predicted_onset("x8_d24_unorm", 0.1)->value);
  EXPECT_FALSE(predicted_onset("d32_sfloat_reversed_z", 0.1).has_value());
  EXPECT_FALSE(predicted_onset("d32_sfloat_reversed_z_float", 0.1).has_value());
  EXPECT_EQ(case_depth_format("x8_d24_unorm_reversed_z_float"), "x8_d24_unorm");
  EXPECT_EQ(case_depth_mapping("x8_d24_unorm_reversed_z"), DepthMapping::ReversedDouble);
  EXPECT_EQ(case_depth_mapping("d16_unorm"), DepthMapping::StandardFloat);
}

// The smallest offset that separates a coplanar pair is clean itself: its bracket is closed there.
TEST(ExperimentsCharts, CoplanarOffsetPredictionIsCleanAtItsValue) {
  const auto d16 = predicted_boundary("coplanar_offset", "d16_unorm", "exact");
  ASSERT_TRUE(d16.has_value());
  EXPECT_TRUE(d16->clean_at_value);
  // D16's two triangulations store the same depth (D = 0): c = (0 + 1) / 2.
  EXPECT_EQ(d16->value, 0.5);
  FailureBoundary measured{"coplanar_offset", "depth", "d16_unorm", "exact", 0.25, 0.5, 9, 2, 0, {}};
  EXPECT_TRUE(check_bracket(measured, 0.5, true).in_bracket);
  EXPECT_FALSE(check_bracket(measured, 0.5, false).in_bracket);
  EXPECT_FALSE(check_bracket(measured, 0.25, true).in_bracket);
  EXPECT_TRUE(boundary_json(measured)["predicted_in_bracket"].get<bool>());
}

}  // namespace
}  // namespace rastercmp::experiments
