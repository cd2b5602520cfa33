// Experiment building blocks that need no device: the append-only CSV and its resume, the
// Pareto front, chart labels, number formatting, the scene builders' invariants.
#include <cmath>
#include <filesystem>
#include <map>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include <gtest/gtest.h>

#include "experiments/chart_labels.hpp"
#include "experiments/depth_precision.hpp"
#include "experiments/resolution_sweep.hpp"
#include "experiments/summary_figure.hpp"
#include "experiments/csv_log.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/order_stats.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/scene_needs.hpp"
#include "experiments/skip_savings.hpp"
#include "experiments/speed_accuracy.hpp"
#include "experiments/sweep_common.hpp"
#include "model/errors.hpp"
#include "tests/test_temp_dir.hpp"

namespace rastercmp::experiments {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir(const std::string& name) { return test_support::fresh_temp_dir("experiments_units_" + name); }

TEST(ExperimentsCsv, ResumeKeepsCompleteRowsAndDropsACutOffRow) {
  const fs::path path = temp_dir("csv") / "points.csv";
  {
    CsvAppender csv(path.string(), {"a", "b", "value"}, 2, false);
    csv.append({"1", "x", "0.5"});
    csv.append({"2", "x", "0.25"});
  }
  std::ofstream(path, std::ios::app) << "3,x,0.1";  // interrupted mid-row: no newline
  CsvAppender resumed(path.string(), {"a", "b", "value"}, 2, true);
  EXPECT_EQ(resumed.rows_kept(), 2u);
  EXPECT_TRUE(resumed.has({"1", "x"}));
  EXPECT_TRUE(resumed.has({"2", "x", "ignored"}));
  EXPECT_FALSE(resumed.has({"3", "x"}));
  resumed.append({"3", "x", "0.125"});
  const CsvTable table = read_csv(path.string());
  ASSERT_EQ(table.rows.size(), 3u);
  EXPECT_EQ(table.rows[2][2], "0.125");
}

TEST(ExperimentsCsv, ResumeRefusesAnotherHeader) {
  const fs::path path = temp_dir("header") / "points.csv";
  { CsvAppender csv(path.string(), {"a", "b"}, 1, false); }
  EXPECT_THROW(CsvAppender(path.string(), {"a", "c"}, 1, true), InputError);
  EXPECT_NO_THROW(CsvAppender(path.string(), {"a", "c"}, 1, false));  // a fresh run starts over
}

TEST(ExperimentsNumbers, ShortestRoundTrip) {
  for (double v : {0.1, 2.0 / 65535.0, 1e6, std::pow(10.0, 2.5), -1e-7})
    EXPECT_EQ(std::strtod(num(v).c_str(), nullptr), v) << num(v);
  EXPECT_EQ(num(std::nan("")), "nan");
  EXPECT_EQ(num(-INFINITY), "-inf");
}

TEST(ExperimentsPareto, KeepsOnlyPointsNothingBeatsOnBothAxes) {
  const std::vector<EntrySummary> entries = {{"f", "slow exact", 4.0, 0.0, 0.0},
                                             {"f", "fast rough", 1.0, 5.0, 9.0},
                                             {"f", "dominated", 3.0, 6.0, 1.0},
                                             {"f", "middle", 2.0, 1.0, 1.0}};
  EXPECT_EQ(pareto_front(entries, true), (std::vector<size_t>{1, 3, 0}));
  EXPECT_EQ(pareto_front(entries, false), (std::vector<size_t>{1, 3, 0}));
}

// The distribution-free interval of a median: ranks from Binomial(n, 1/2) (order_stats.hpp).
TEST(ExperimentsOrderStats, MedianIntervalRanksFromTheBinomial) {
  // n = 15: P(B <= 3) = 576 / 32768 <= 0.025 < P(B <= 4), so ranks 4 and 12, coverage 1 - 2 * 576 / 32768.
  std::vector<double> values;
  for (int i = 15; i >= 1; --i) values.push_back(i * 10.0);  // unsorted on purpose
  const MedianCi ci = median_ci(values);
  EXPECT_EQ(ci.median, 80.0);
  EXPECT_EQ(ci.low_rank, 4u);
  EXPECT_EQ(ci.high_rank, 12u);
  EXPECT_EQ(ci.low, 40.0);
  EXPECT_EQ(ci.high, 120.0);
  EXPECT_NEAR(ci.coverage, 1 - 2 * 576.0 / 32768.0, 1e-12);
  // n = 5 cannot reach 95%: the whole range, coverage 1 - 2 / 32.
  const MedianCi small = median_ci({3, 1, 2, 5, 4});
  EXPECT_EQ(small.median, 3.0);
  EXPECT_EQ(small.low, 1.0);
  EXPECT_EQ(small.high, 5.0);
  EXPECT_NEAR(small.coverage, 1 - 2.0 / 32.0, 1e-12);
  // Even n: the mean of the middle two; an outlier moves neither the median nor the interval.
  std::vector<double> noisy{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20};
  const MedianCi before = median_ci(noisy);
  noisy.back() = 1e9;
  const MedianCi after = median_ci(noisy);
  EXPECT_EQ(before.median, 10.5);
  EXPECT_EQ(after.median, before.median);
  EXPECT_EQ(after.low, before.low);
  EXPECT_EQ(after.high, before.high);
  EXPECT_GE(after.coverage, 0.95);
  EXPECT_THROW(median_ci({1.0}, 1.0), std::invalid_argument);
}

// Each family's front holds its own methods with the exact and fast paths, never another family's.
TEST(ExperimentsPareto, FamilyFrontsIncludeTheExactAndFastPaths) {
  const std::vector<EntrySummary> entries = {{"exact path", "exact", 4.0, 0.0, 0.0},
                                             {"fast path", "threads=2", 2.0, 0.0, 0.0},
                                             {"fill", "scanline", 1.0, 0.5, 0.5},
                                             {"fill", "slow and wrong", 9.0, 0.9, 0.9},
                                             {"line", "dda", 0.5, 3.0, 3.0}};
  const auto fronts = family_pareto_fronts(entries, true);
  ASSERT_EQ(fronts.size(), 2u);
  EXPECT_EQ(fronts[0].first, "fill");
  EXPECT_EQ(fronts[0].second, (std::vector<size_t>{2, 1}));  // scanline, then the fast path
  EXPECT_EQ(fronts[1].first, "line");
  EXPECT_EQ(fronts[1].second, (std::vector<size_t>{4, 1}));
}

TEST(ExperimentsChartLabels, FarPointsKeepTheirOwnLabels) {
  const ChartAxes axes{false, 0, 100, 0, 100};
  const auto labels = cluster_labels({{10, 10, 1}, {80, 10, 2}, {10, 80, 3}}, axes);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0].text, "1");
  EXPECT_EQ(labels[1].text, "2");
  EXPECT_EQ(labels[2].text, "3");
}

TEST(ExperimentsChartLabels, ClosePointsShareOneLabelAtTheLeftmostPoint) {
  const ChartAxes axes{false, 0, 100, 0, 100};
  const auto labels = cluster_labels({{12, 50, 7}, {10, 51, 3}, {60, 50, 9}}, axes);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].text, "3,7");  // ascending, whatever the input order
  EXPECT_EQ(labels[0].x, 10);
  EXPECT_EQ(labels[0].y, 51);
  EXPECT_EQ(labels[1].text, "9");
}

TEST(ExperimentsChartLabels, AGrowingLabelSwallowsTheLabelItNowReaches) {
  // 1..6 sit 2% apart on one row; 7 is 16% to the right of 1: alone its label would be clear of
  // "1", but "1,2,3,4,5,6" (11 characters, 12% wide) plus the margins reaches it.
  const ChartAxes axes{false, 0, 100, 0, 100};
  std::vector<ChartPoint> points;
  for (int i = 0; i < 6; ++i) points.push_back({10.0 + 2 * i, 0, i + 1});
  points.push_back({26, 0, 7});
  const auto labels = cluster_labels(points, axes);
  ASSERT_EQ(labels.size(), 1u);
  EXPECT_EQ(labels[0].text, "1,2,3,4,5,6,7");
  const auto apart = cluster_labels({{10, 0, 1}, {26, 0, 7}}, axes);
  EXPECT_EQ(apart.size(), 2u);
}

TEST(ExperimentsChartLabels, LogAxisMeasuresDistanceInDecades) {
  // 1 ms and 1.1 ms are 0.014 of a 3-decade axis apart; 0.1 ms and 0.2 ms are 0.1 apart.
  const ChartAxes axes{true, 1e-4, 1e-1, 0, 1};
  EXPECT_EQ(cluster_labels({{1e-3, 0, 1}, {1.1e-3, 0, 2}}, axes).size(), 1u);
  EXPECT_EQ(cluster_labels({{1e-4, 0.5, 1}, {2e-4, 0.5, 2}}, axes).size(), 2u);
}

TEST(ExperimentsScenes, DecalSceneBiasSignAndDraws) {
  PairParams p;
  p.kind = PairKind::NearCoplanar;
  p.separation = 0.5;
  p.decal_bias.enable = true;
  p.decal_bias.constant_factor = -2;
  const DecalScene decal = make_decal_scene(p);
  ASSERT_EQ(decal.scene.draws.size(), 2u);
  EXPECT_EQ(decal.decal_draw, 1u);
  EXPECT_EQ(decal.scene.draws[1].state.depth_bias.constant_factor, -2.0f);
  EXPECT_FALSE(decal.scene.draws[0].state.depth_bias.enable);
  // The decal lies in front: its clip-space depth (z/w) is smaller at the centre of the view.
  const glm::vec4 base = decal.scene.draws[0].positions_clip[0], front = decal.scene.draws[1].positions_clip[0];
  EXPECT_GT(base.w, 0.0f);
  EXPECT_GT(front.w, 0.0f);
  const Scene alone = decal_only(decal);
  ASSERT_EQ(alone.draws.size(), 1u);
  EXPECT_FALSE(alone.draws[0].state.depth.test_enable);
}

// The four clip-z mappings of depth_far_near and fight_onset: the same eye distances, z formed as
// each says; reversed maps near to 1 and far to 0 with compare Greater and clear 0.
TEST(ExperimentsScenes, DepthMappingsFormClipZFromW) {
  PairParams p;
  p.kind = PairKind::NearCoplanar;
  p.separation = 0.1;
  p.far_near_ratio = 1e5;
  const Scene standard = make_decal_scene(p).scene;
  const double n = p.far_plane / p.far_near_ratio, f = p.far_plane;
  const Scene dbl = with_depth_mapping(standard, DepthMapping::StandardDouble, n, f);
  const Scene rev = with_depth_mapping(standard, DepthMapping::ReversedDouble, n, f);
  const Scene rev_float = with_depth_mapping(standard, DepthMapping::ReversedFloat, n, f);
  const glm::vec4 v = standard.draws[0].positions_clip[0];
  EXPECT_EQ(dbl.draws[0].positions_clip[0].z, float(f * (double(v.w) - n) / (f - n)));
  EXPECT_NEAR(double(v.z), f * (double(v.w) - n) / (f - n), 1e-5);  // the camera matrix's float z
  EXPECT_EQ(rev.draws[0].positions_clip[0].z, float(n * (f - double(v.w)) / (f - n)));
  EXPECT_NEAR(double(rev_float.draws[0].positions_clip[0].z), n * (f - double(v.w)) / (f - n), 1e-9);
  EXPECT_EQ(rev.draws[1].state.depth.compare_op, CompareOp::Greater);
  EXPECT_EQ(rev_float.depth_clear, 0.0f);
  EXPECT_EQ(dbl.draws[1].state.depth.compare_op, standard.draws[1].state.depth.compare_op);
  EXPECT_EQ(std::string(mapping_suffix(DepthMapping::ReversedFloat)), "_reversed_z_float");
}

// The jitter ensemble: jitter 0 is the plain placement; the others differ in x, y and depth phase.
TEST(ExperimentsScenes, EnsembleJittersAreSubPixelAndDistinct) {
  EXPECT_EQ(ensemble_jitter(0).x_px, 0.0);
  EXPECT_EQ(ensemble_jitter(0).depth_phase, 0.0);
  std::set<double> xs;
  for (int j = 1; j < 8; ++j) {
    const Jitter jitter = ensemble_jitter(j);
    EXPECT_GT(jitter.x_px, 0.0);
    EXPECT_LT(jitter.x_px, 1.0);
    EXPECT_LT(jitter.y_px, 1.0);
    EXPECT_LT(jitter.depth_phase, 1.0);
    xs.insert(jitter.x_px + 10 * jitter.y_px);
  }
  EXPECT_EQ(xs.size(), 7u);
  PairParams p;
  p.kind = PairKind::NearCoplanar;
  const Scene plain = make_decal_scene(p).scene;
  p.jitter_x_px = 0.5;
  const Scene moved = make_decal_scene(p).scene;
  const glm::vec4 a = plain.draws[0].positions_clip[0], b = moved.draws[0].positions_clip[0];
  EXPECT_NEAR((double(b.x) / b.w - double(a.x) / a.w) * plain.width / 2, 0.5, 1e-4);
}

// The identical-vertex control on the exact path (which equals lavapipe): one triangle drawn twice,
// the second loses every pixel without offset and wins every pixel with constant offset 1 r, on
// every depth format (test_experiments_sweeps checks lavapipe's render of the same points).
TEST(ExperimentsScenes, IdenticalTriangleIsSeparatedByOneR) {
  for (DepthFormat format : sweep_depth_formats())
    for (double angle : {0.0, 60.0})
      for (float constant : {0.0f, 1.0f}) {
        PairParams p;
        p.kind = PairKind::Identical;
        p.format = format;
        p.angle_deg = angle;
        p.decal_bias = {constant != 0, -constant, 0, 0};
        const DecalScene decal = make_decal_scene(p);
        ASSERT_EQ(decal.scene.draws[0].positions_clip, decal.scene.draws[1].positions_clip);
        ASSERT_EQ(decal.scene.draws[0].positions_clip.size(), 3u);
        const RenderResult both = render_cpu(decal.scene, exact_cpu_options());
        const std::vector<bool> mask = covered_mask(render_cpu(decal_only(decal), exact_cpu_options()));
        ASSERT_GT(count(mask), 100u);
        EXPECT_EQ(wrong_surface_fraction(both, mask, 1), constant == 0 ? 1.0 : 0.0)
            << to_string(format) << " angle " << angle << " constant " << constant;
      }
}

TEST(ExperimentsScenes, FarTriangleReachesTheViewportBoundsLimit) {
  const Scene scene = make_far_triangle(32767);
  ASSERT_TRUE(scene.viewport.has_value());
  EXPECT_EQ(double(scene.viewport->x) + scene.viewport->width, 32767.0);
  EXPECT_LE(scene.viewport->width, float(kMaxFramebufferSide));
  EXPECT_EQ(scene.width, kMaxFramebufferSide);
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(ExperimentsCharts, TitlesAndLabelsAreNotEnhancedText) {
  const std::string body = noenhanced_text(
      "set title 'near_coplanar'\nset xlabel 'a_b'\nset ylabel 'c' noenhanced\nset format x '10^{%L}'\n");
  EXPECT_EQ(body,
            "set title 'near_coplanar' noenhanced\nset xlabel 'a_b' noenhanced\nset ylabel 'c' noenhanced\n"
            "set format x '10^{%L}'\n");
}

TEST(ExperimentsCharts, ZeroOnALogAxisGoesToALabelledFloor) {
  EXPECT_DOUBLE_EQ(log_axis_floor({0, 0.5, 3, 100}), 0.01);
  EXPECT_DOUBLE_EQ(log_axis_floor({0, 20}), 1);
  EXPECT_DOUBLE_EQ(log_axis_floor({0}), 0.1);
  EXPECT_EQ(zero_tic_command("x", 0.01), "set xtics add ('0' 0.01)\n");
}

// A chart with 12 series and a title with underscores, through gnuplot when it is installed: the
// title prints as written and every series has its own colour and dash pattern.
TEST(ExperimentsCharts, TwelveSeriesGetDistinctStylesAndUnderscoresSurvive) {
  const fs::path dir = temp_dir("charts");
  std::vector<DataBlock> blocks;
  for (int i = 0; i < 12; ++i)
    blocks.push_back(
        {"series_" + std::to_string(i),
         {{"\"series_" + std::to_string(i) + "\"", "x"}, {"1", std::to_string(i)}, {"2", std::to_string(i)}}});
  ASSERT_NO_THROW(find_gnuplot()) << "gnuplot is not installed (scripts/setup.sh installs it)";
  render_chart(dir.string(), "many", blocks,
               "set title 'near_coplanar'\nplot for [i=0:11] DATA index i using 1:2 title columnheader(1) with lines "
               "lt (i+1)\n");
  const std::string svg = read_text(dir / "many.svg");
  EXPECT_NE(svg.find("near_coplanar"), std::string::npos);
  EXPECT_EQ(svg.find("near_{c}oplanar"), std::string::npos);
  EXPECT_NE(svg.find("series_11"), std::string::npos);
  const std::string script = read_text(dir / "many.gp");
  std::set<std::string> colours, styles;
  const std::regex linetype("set linetype (\\d+) lc rgb '(#[0-9a-f]{6})' lw [0-9.]+ dt (\\d) pt (\\d+)");
  for (std::sregex_iterator it(script.begin(), script.end(), linetype), end; it != end; ++it)
    if (std::stoi((*it)[1]) <= 12) {
      colours.insert((*it)[2]);
      styles.insert((*it)[2].str() + "/" + (*it)[3].str() + "/" + (*it)[4].str());
    }
  EXPECT_EQ(colours.size(), 12u);
  EXPECT_EQ(styles.size(), 12u);
}

TEST(ExperimentsPage, RendersFromTheTemplateWithEscaping) {
  const std::string html = index_html(
      "Polygon <offset>", {{"Z & fighting", "a < b", {"zfight_far_near_near_coplanar"}, {{"h1", "h2"}, {"1", "x\"y"}}}},
      {"polygon_offset.csv"});
  EXPECT_NE(html.find("<title>Polygon &lt;offset&gt;</title>"), std::string::npos) << html;
  EXPECT_NE(html.find("<h2>Z &amp; fighting</h2>"), std::string::npos);
  EXPECT_NE(html.find("<p>a &lt; b</p>"), std::string::npos);
  EXPECT_NE(html.find("<th>h1</th><th>h2</th>"), std::string::npos);
  EXPECT_NE(html.find("<td>x&quot;y</td>"), std::string::npos);
  EXPECT_NE(html.find("<img src=\"zfight_far_near_near_coplanar.svg\""), std::string::npos);
  EXPECT_NE(html.find("<li><a href=\"polygon_offset.csv\">polygon_offset.csv</a></li>"), std::string::npos);
  EXPECT_EQ(index_html("t", {{"no table", "", {}}}, {}).find("<table>"), std::string::npos);
}

// Which stages a scene needs, from its state alone (scene_needs.hpp).
TEST(ExperimentsSceneNeeds, EachStageFromTheStateThatRequiresIt) {
  Scene plain = make_sliver_pair(3, 20);  // two triangles inside the frame, D32, no bias, no culling
  StageNeeds n = scene_needs(plain);
  EXPECT_FALSE(n.clipping);
  EXPECT_TRUE(n.depth);
  EXPECT_FALSE(n.bias || n.msaa || n.lines || n.culling);

  EXPECT_TRUE(scene_needs(make_near_w_triangle(1e-3f)).clipping);  // a vertex far outside x <= w
  Scene clip = plain;
  clip.draws[0].positions_clip[0].z = -0.5f;  // behind the near plane: outside with depth clipping only
  EXPECT_TRUE(scene_needs(clip).clipping);
  clip.draws[0].state.depth_clamp = true;
  EXPECT_FALSE(scene_needs(clip).clipping);

  Scene depthless = plain;
  depthless.depth_format = DepthFormat::None;
  EXPECT_FALSE(scene_needs(depthless).depth);
  Scene test_off = plain;
  for (Draw& d : test_off.draws) d.state.depth.test_enable = false;
  EXPECT_FALSE(scene_needs(test_off).depth);

  Scene bias = plain;
  bias.draws[1].state.depth_bias = {true, 0, 0, 0.5f};  // on, but both factors 0: nothing to add
  EXPECT_FALSE(scene_needs(bias).bias);
  bias.draws[1].state.depth_bias.slope_factor = 1;
  EXPECT_TRUE(scene_needs(bias).bias);

  Scene msaa = plain;
  msaa.samples = 4;
  EXPECT_TRUE(scene_needs(msaa).msaa);
  EXPECT_TRUE(scene_needs(make_line_star(64, 8)).lines);
  Scene wire = plain;
  wire.draws[0].state.polygon_mode = PolygonMode::Line;
  EXPECT_TRUE(scene_needs(wire).lines);
  Scene culled = plain;
  culled.draws[1].state.cull_mode = CullMode::Back;
  EXPECT_TRUE(scene_needs(culled).culling);

  EXPECT_EQ(with_skip_off(CpuOptions{}, "all").skips.clip_only_when_needed, false);
  EXPECT_THROW(with_skip_off(CpuOptions{}, "edges"), std::invalid_argument);
}

// chart scene-needs --quick, end to end on a two-scene suite (CPU and gnuplot only): one row per
// scene, and a skip is timed only where the timing scene does not need its stage.
TEST(ExperimentsSceneNeeds, QuickRunTimesOnlySkippedStages) {
  ASSERT_NO_THROW(find_gnuplot()) << "gnuplot is not installed (scripts/setup.sh installs it)";
  const fs::path dir = fs::temp_directory_path() / "rastercmp_test_experiments_scene_needs";
  fs::remove_all(dir);
  run_scene_needs({dir.string(), true, false}, {{"a.sliver", make_sliver_pair(3, 20)}, {"b.lines", make_line_star(64, 8)}});
  const CsvTable needs = read_csv((dir / kSceneNeedsCsv).string());
  ASSERT_EQ(needs.rows.size(), 2u);
  EXPECT_EQ(needs.rows[1][needs.column("lines")], "needs");
  EXPECT_EQ(needs.rows[0][needs.column("lines")], "skips");
  const CsvTable savings = read_csv((dir / kSkipSavingsCsv).string());
  ASSERT_FALSE(savings.rows.empty());
  std::map<std::string, Scene> timing;
  for (auto& [name, scene] : skip_timing_scenes(true)) timing[name] = scene;
  for (const auto& row : savings.rows) {
    const std::string& skip = row[savings.column("skip")];
    ASSERT_TRUE(timing.count(row[0])) << row[0];
    const StageNeeds n = scene_needs(timing[row[0]]);
    EXPECT_FALSE(skip == "clip" && n.clipping) << row[0];
    EXPECT_FALSE(skip == "depth" && n.depth) << row[0];
    EXPECT_FALSE(skip == "bias" && n.bias) << row[0];
    EXPECT_GT(std::stod(row[savings.column("ratio")]), 0.0);
  }
  // The depthless grid skips clipping, depth and bias: all three are timed there.
  size_t depthless = 0;
  for (const auto& row : savings.rows) depthless += row[0].find("depthless") != std::string::npos ? 1 : 0;
  EXPECT_EQ(depthless, 4u);  // clip, depth, bias, all
  for (const char* chart : {"suite_needs", "skip_savings"})
    EXPECT_NE(read_text(dir / (std::string(chart) + ".svg")).find("<svg"), std::string::npos) << chart;
}

// chart depth-precision: the stage functions store what render_cpu stores, at the bucket's edges too.
TEST(DepthPrecision, StageFunctionsStoreWhatTheRendererStores) {
  const DepthPlanes planes;
  for (DepthFormat format : sweep_depth_formats())
    for (PrecisionMapping mapping : kPrecisionMappings)
      for (float w : {0.13f, 1.7f, 42.0f, 777.0f}) {
        EXPECT_EQ(stored_depth_raw(format, mapping, w, planes), rendered_depth_raw(format, mapping, w, planes))
            << to_string(format) << " " << to_string(mapping) << " w " << w;
        const DepthBucket b = depth_bucket(format, mapping, w, planes);
        ASSERT_FALSE(b.open) << to_string(format) << " " << to_string(mapping) << " w " << w;
        EXPECT_LE(b.w_low, w);
        EXPECT_GE(b.w_high, w);
        EXPECT_EQ(rendered_depth_raw(format, mapping, b.w_high, planes), b.raw);
        EXPECT_NE(rendered_depth_raw(format, mapping, std::nextafter(b.w_high, 1e30f), planes), b.raw);
        EXPECT_NE(rendered_depth_raw(format, mapping, std::nextafter(b.w_low, 0.0f), planes), b.raw);
      }
}

// Where theory holds (D16: its step is 2^8 times the float rounding of z), the measured bucket is the
// ideal one within 1.5%, and the first-order analytic step w^2 (f - n) / (f n (2^16 - 1)) within 1.5%
// plus the bucket's own relative width (the slope changes across it).
TEST(DepthPrecision, D16MeasuredStepMatchesTheAnalyticOne) {
  const DepthPlanes planes;
  for (PrecisionMapping mapping : kPrecisionMappings)
    for (float w : eye_distances(planes, 2)) {
      const DepthBucket b = depth_bucket(DepthFormat::D16Unorm, mapping, w, planes);
      if (b.open) continue;
      const double measured = b.width(), ideal = ideal_bucket_width(DepthFormat::D16Unorm, mapping, w, planes);
      const double analytic = analytic_step(DepthFormat::D16Unorm, mapping, w, planes);
      EXPECT_NEAR(measured / ideal, 1.0, 0.015) << to_string(mapping) << " w " << w;
      EXPECT_NEAR(measured / analytic, 1.0, 0.015 + 2 * measured / w) << to_string(mapping) << " w " << w;
      if (mapping == PrecisionMapping::Standard) {  // the textbook form, written out
        EXPECT_NEAR(analytic, double(w) * w * (1000 - 0.1) / (1000 * 0.1 * 65535), 1e-12 * analytic);
      }
    }
}

// Float32: the D32 step can never be finer than the float spacing of w itself, and on the infinite
// reversed mapping (z = n / w) the ideal bucket is a fixed fraction of w (2^-23 .. 2^-24 relative).
TEST(DepthPrecision, D32StepIsBoundedByTheFloatSpacingOfW) {
  const DepthPlanes planes;
  for (float w : eye_distances(planes, 2)) {
    const DepthBucket b = depth_bucket(DepthFormat::D32Sfloat, PrecisionMapping::ReversedInfinite, w, planes);
    EXPECT_GE(b.width(), float_spacing(w)) << w;
    const double relative = ideal_bucket_width(DepthFormat::D32Sfloat, PrecisionMapping::ReversedInfinite, w, planes) / w;
    EXPECT_GE(relative, std::ldexp(1.0, -25)) << w;
    EXPECT_LE(relative, std::ldexp(1.0, -22)) << w;
  }
}

// chart resolution: the exponent fit, and the rule on two methods whose error is clear-cut: DDA's
// lines differ along their length (count ~ size), bilinear depth inside every triangle (~ size^2).
TEST(ResolutionSweep, ExponentOfAPowerLaw) {
  std::vector<ResolutionPoint> points;
  for (uint32_t size : {64u, 128u, 256u}) points.push_back({"f", "m", size, 0, 0, 0, size_t(size) * size * 3});
  EXPECT_NEAR(count_exponent(points), 2.0, 1e-12);
  points.push_back({"f", "m", 512, 0, 0, 0, 0});  // a zero count is left out of the fit
  EXPECT_NEAR(count_exponent(points), 2.0, 1e-12);
  EXPECT_TRUE(std::isnan(count_exponent({points[0]})));
}

TEST(ResolutionSweep, EdgeErrorsGrowWithSizeAndAreaErrorsWithItsSquare) {
  std::vector<ResolutionMethod> chosen;
  for (const ResolutionMethod& m : resolution_methods())
    if (m.method == "line=dda" || m.method == "depth=bilinear") chosen.push_back(m);
  ASSERT_EQ(chosen.size(), 2u);
  const std::vector<uint32_t> sizes = {64, 128, 256, 512};
  const std::vector<ResolutionPoint> points = measure_resolution(chosen, sizes);
  for (size_t k = 0; k < chosen.size(); ++k) {
    const std::vector<ResolutionPoint> series(points.begin() + long(k * sizes.size()),
                                              points.begin() + long((k + 1) * sizes.size()));
    for (const ResolutionPoint& p : series) {
      EXPECT_GT(p.either, 0u) << p.method << " " << p.size;
      EXPECT_EQ(p.samples, size_t(p.size) * p.size * (chosen[k].lines ? 2 : 4));
    }
    EXPECT_NEAR(count_exponent(series), chosen[k].predicted_exponent, kExponentTolerance) << chosen[k].method;
  }
  EXPECT_EQ(chosen[0].predicted_exponent + chosen[1].predicted_exponent, 3);  // one edge, one area
}

// chart summary: it reads each source's fields (and ignores fields it does not know), normalises
// by the prediction, and names the file and the field of a bad input.
TEST(SummaryFigure, ReadsEachSourceAndNamesABadField) {
  const fs::path dir = temp_dir("summary");
  std::ofstream(dir / "stability.json")
      << R"({"boundaries": [{"experiment": "depth_far_near", "family": "depth", "case": "d16_unorm", "method": "exact",
            "last_clean": 177.8, "boundary": 316.2, "predicted": 241, "measured_low": 177.8, "measured_high": 316.2,
            "predicted_in_bracket": true, "a_field_added_later": [1, 2]},
           {"experiment": "fill_fan", "family": "fill", "case": "fan", "method": "scanline", "boundary": 0.5}]})";
  std::ofstream(dir / "depth_r.json")
      << R"([{"format": "d16_unorm", "r_cpu": 3.0e-5, "r_vulkan": 3.0e-5, "predicted": 3.0e-5}])";
  std::ofstream(dir / "zfight.json")
      << R"({"series": [{"format": "d16_unorm", "mapping": "standard", "measured_onset_above": 10,
            "measured_onset_at_most": 31.6, "predicted_onset": 20, "predicted_onset_interval": [10, 31.6],
            "calibration": true, "agrees": true}]})";
  const std::vector<SummaryRow> rows = read_summary_inputs({dir.string()});
  ASSERT_EQ(rows.size(), 3u);  // the boundary without a prediction is not a row
  EXPECT_EQ(rows[0].family, "depth");
  EXPECT_NEAR(rows[0].low, 177.8 / 241, 1e-12);
  EXPECT_NEAR(rows[0].high, 316.2 / 241, 1e-12);
  EXPECT_TRUE(rows[0].agrees);
  EXPECT_EQ(rows[1].source, "zfight.json");
  EXPECT_NEAR(rows[1].predicted_high, 31.6 / 20, 1e-12);
  EXPECT_EQ(rows[2].source, "depth_r.json");
  EXPECT_TRUE(rows[2].agrees);

  std::ofstream(dir / "zfight.json") << R"({"series": [{"format": "d16_unorm", "mapping": "standard",
      "measured_onset_above": 10, "measured_onset_at_most": "31.6", "predicted_onset": 20}]})";
  try {
    read_summary_inputs({dir.string()});
    FAIL() << "a string where a number belongs was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), (dir / "zfight.json").string());
    EXPECT_EQ(e.json_path(), "$.series[0].measured_onset_at_most");
  }
  EXPECT_THROW(read_summary_inputs({(dir / "no_such_folder").string()}), UsageError);
}

}  // namespace
}  // namespace rastercmp::experiments
