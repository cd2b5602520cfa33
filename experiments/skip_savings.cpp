#include "experiments/skip_savings.hpp"

#include <filesystem>
#include <stdexcept>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "bench/skip_scenes.hpp"
#include "experiments/csv_log.hpp"
#include "experiments/doc_table_renderers.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/order_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/scene_make.hpp"
#include "experiments/scene_needs.hpp"
#include "experiments/speed_accuracy.hpp"
#include "model/host.hpp"

namespace rastercmp::experiments {
namespace {

// Thread CPU time (as bench/bench_skips.cpp measures): the exact path (threads = 0) renders on
// the calling thread, and the other processes of a shared machine then count less than in wall time.
double seconds_of(const Scene& scene, const CpuOptions& cpu) {
  const double start = thread_cpu_seconds();
  const RenderResult result = render_cpu(scene, cpu);
  const double seconds = thread_cpu_seconds() - start;
  if (result.owner.empty()) throw std::logic_error("empty render");  // keeps the render observable
  return seconds;
}

struct Saving {
  std::string scene, skip, stages;  // stages: the skipped stages the skip covers
  MedianCi on_ms, off_ms, ratio;
};

// Skips to time on a scene: each one whose stage the scene does not need, then "all" of them.
std::vector<std::pair<std::string, std::string>> skips_for(const StageNeeds& needs) {
  std::vector<std::pair<std::string, std::string>> out;
  std::string all;
  for (const StageInfo& stage : pipeline_stages())
    if (stage.skip && !stage.needed(needs)) {
      out.push_back({*stage.skip, stage.name});
      all += (all.empty() ? "" : "+") + stage.name;
    }
  if (out.size() > 1) out.push_back({"all", all});
  return out;
}

Saving measure_saving(const std::string& name, const Scene& scene, const std::string& skip, const std::string& stages,
                      int repeats) {
  const CpuOptions on = exact_cpu_options(), off = with_skip_off(on, skip);
  seconds_of(scene, on);  // warm the caches, untimed
  std::vector<double> on_ms, off_ms, ratio;
  for (int rep = 0; rep < repeats; ++rep) {
    double a = 0, b = 0;
    if (rep % 2 == 0) {
      a = seconds_of(scene, on);
      b = seconds_of(scene, off);
    } else {
      b = seconds_of(scene, off);
      a = seconds_of(scene, on);
    }
    on_ms.push_back(a * 1e3);
    off_ms.push_back(b * 1e3);
    ratio.push_back(b / a);
  }
  return {name, skip, stages, median_ci(on_ms), median_ci(off_ms), median_ci(ratio)};
}

std::string yes_no(bool v) { return v ? "needs" : "skips"; }

void chart_suite(const std::string& dir, const std::vector<StageNeeds>& needs) {
  const DataBlock block = suite_needs_block(needs);
  render_chart(dir, "suite_needs", {block},
               "set title " + gp_quote(fmt::format("Which stages the {} scenes of the suite need", needs.size())) +
                   "\nset termoption noenhanced\nset style data histograms\nset style histogram rowstacked\n"
                   "set style fill solid 0.8 border lc rgb '#000000'\nset boxwidth 0.6\nset xrange [-0.6:" +
                   std::to_string(block.rows.size()) +
                   "-0.4]\nset ylabel 'scenes'\nset yrange [0:*]\nset key below horizontal\nset grid ytics\n"
                   "plot DATA using 2:xtic(1) title 'needs' lc rgb '#d62728' lw 1 dt 1, '' using 3 title 'skips' "
                   "lc rgb '#2ca02c' lw 1 dt 1\n");
}

void chart_savings(const std::string& dir, const std::vector<Saving>& savings) {
  DataBlock block{"savings", {{"i", "ratio", "low", "high"}}};
  std::string tics;
  for (size_t i = 0; i < savings.size(); ++i) {
    const Saving& s = savings[i];
    block.rows.push_back({std::to_string(i), num(s.ratio.median), num(s.ratio.low), num(s.ratio.high)});
    tics += (i ? ", " : "") + gp_quote(s.scene + ": " + s.stages) + " " + std::to_string(i);
  }
  render_chart(dir, "skip_savings", {block},
               "set title 'What each skipped stage saves: exact path time with the skip off / on (bars: 95% interval)'\n"
               "set termoption noenhanced\nset xtics (" + tics + ") rotate by -35 font ',9'\nset xrange [-0.6:" + std::to_string(savings.size()) +
                   "-0.4]\nset ylabel 'time with the work done / time with it skipped'\nset grid ytics\n"
                   "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb '#888888'\n"
                   "set bmargin 10\nset key off\n"
                   "plot DATA using 1:2:3:4 with yerrorbars pt 7 ps 1.5 lc rgb '#1f77b4'\n");
}

}  // namespace

DataBlock suite_needs_block(const std::vector<StageNeeds>& needs) {
  DataBlock block{"stage needs skips", {}};  // the title is the comment line; every row is data
  for (const StageInfo& stage : pipeline_stages()) {
    size_t count = 0;
    for (const StageNeeds& n : needs) count += stage.needed(n) ? 1 : 0;
    block.rows.push_back({stage.name, std::to_string(count), std::to_string(needs.size() - count)});
  }
  return block;
}

std::vector<std::pair<std::string, Scene>> skip_timing_scenes(bool quick) {
  // The jittered grid meshes of the work-skip benchmark (bench/skip_scenes.hpp, docs/cpu-raster.md
  // "What each skip buys"): every vertex inside the frustum, X8D24 LESS, bias off.
  skip_scenes::MeshSpec grid{quick ? 256u : 512u, quick ? 32u : 128u};
  const std::string grid_name = fmt::format("grid_{}_{}", grid.size, grid.cells);
  const Scene inside = skip_scenes::grid_mesh(grid_name, grid);
  grid.format = DepthFormat::None;
  const Scene depthless = skip_scenes::grid_mesh(grid_name + "_depthless", grid);
  PairParams house;
  house.kind = PairKind::House;
  house.far_near_ratio = 3;
  house.decal_bias = {true, -2, -1, 0};  // scenes/house/far_75.json
  return {{grid_name, inside},
          {grid_name + "_depthless", depthless},
          {"mesh_256_24", make_mesh_scene(256, 24)},  // crosses the clip planes: clipping needed
          {"house", make_decal_scene(house).scene},
          {"line_star", make_line_star(256, 64)}};
}

void run_scene_needs(const SweepOptions& options, const std::vector<std::pair<std::string, Scene>>& suite) {
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  const std::filesystem::path dir(options.out_dir);
  std::vector<std::string> header{"scene"};
  for (const StageInfo& stage : pipeline_stages()) header.push_back(stage.name);
  std::vector<StageNeeds> suite_needs;
  {
    CsvAppender csv((dir / kSceneNeedsCsv).string(), header, 1, false);
    for (const auto& [name, scene] : suite) {
      suite_needs.push_back(scene_needs(scene));
      std::vector<std::string> row{name};
      for (const StageInfo& stage : pipeline_stages()) row.push_back(yes_no(stage.needed(suite_needs.back())));
      csv.append(row);
    }
  }
  const int repeats = options.quick ? 5 : 21;
  const std::vector<std::pair<std::string, Scene>> timing = skip_timing_scenes(options.quick);
  size_t planned = 0;
  for (const auto& [name, scene] : timing) planned += skips_for(scene_needs(scene)).size();
  Progress progress("chart scene-needs", planned);
  std::vector<Saving> savings;
  nlohmann::ordered_json json;
  json["repeats"] = repeats;
  // Where the timings were taken (as speed_accuracy.json records it).
  const RunHost host = current_run_host();
  json["host"] = host.host;
  json["cpu_model"] = host.cpu_model;
  json["git_commit"] = host.git_commit;
  json["git_dirty"] = host.git_dirty;
  json["load_average_1min_before"] = run_load_average();
  json["freed_memory_kept"] = options.freed_memory_kept;
  json["timing_scenes"] = nlohmann::ordered_json::array();
  CsvAppender csv((dir / kSkipSavingsCsv).string(),
                  {"scene", "skip", "stages", "on_ms", "off_ms", "ratio", "ratio_ci_low", "ratio_ci_high", "ci_coverage"},
                  2, false);
  for (const auto& [name, scene] : timing) {
    const StageNeeds needs = scene_needs(scene);
    nlohmann::ordered_json entry{{"scene", name}};
    for (const StageInfo& stage : pipeline_stages()) entry[stage.name] = yes_no(stage.needed(needs));
    json["timing_scenes"].push_back(entry);
    for (const auto& [skip, stages] : skips_for(needs)) {
      savings.push_back(measure_saving(name, scene, skip, stages, repeats));
      const Saving& s = savings.back();
      csv.append({name, skip, stages, num(s.on_ms.median), num(s.off_ms.median), num(s.ratio.median),
                  num(s.ratio.low), num(s.ratio.high), num(s.ratio.coverage)});
      progress.finished();
    }
  }
  progress.done();
  json["load_average_1min_after"] = run_load_average();
  json["suite"] = nlohmann::ordered_json::object();
  json["suite"]["scenes"] = suite.size();
  for (const StageInfo& stage : pipeline_stages()) {
    size_t count = 0;
    for (const StageNeeds& n : suite_needs) count += stage.needed(n) ? 1 : 0;
    json["suite"][stage.name] = {{"needs", count}, {"skips", suite.size() - count},
                                 {"work_skip", stage.skip ? nlohmann::ordered_json(*stage.skip) : nlohmann::ordered_json()}};
  }
  json["savings"] = nlohmann::ordered_json::array();
  for (const Saving& s : savings)
    json["savings"].push_back({{"scene", s.scene}, {"skip", s.skip}, {"stages", s.stages}, {"on_ms", s.on_ms.median},
                               {"off_ms", s.off_ms.median}, {"ratio", s.ratio.median}, {"ratio_ci_low", s.ratio.low},
                               {"ratio_ci_high", s.ratio.high}, {"ci_coverage", s.ratio.coverage}});
  write_json_file(options.out_dir, "scene_needs.json", json.dump(2) + "\n");
  write_scene_needs_tables(options.out_dir, json.dump());
  if (!suite_needs.empty()) chart_suite(options.out_dir, suite_needs);
  chart_savings(options.out_dir, savings);

  std::vector<std::vector<std::string>> stage_table{{"stage", "scenes that need it", "scenes that skip it", "work skip"}};
  for (const auto& stage : json["suite"].items())
    if (stage.key() != "scenes")
      stage_table.push_back({stage.key(), std::to_string(stage.value()["needs"].get<size_t>()),
                             std::to_string(stage.value()["skips"].get<size_t>()),
                             stage.value()["work_skip"].is_null() ? "none (no work when absent)"
                                                                  : stage.value()["work_skip"].get<std::string>()});
  std::vector<std::vector<std::string>> saving_table{
      {"scene", "skipped stages", "skip turned off", "ms skipped", "ms done", "done / skipped", "95% interval"}};
  for (const Saving& s : savings)
    saving_table.push_back({s.scene, s.stages, s.skip, fmt::format("{:.3f}", s.on_ms.median),
                            fmt::format("{:.3f}", s.off_ms.median), fmt::format("{:.3f}", s.ratio.median),
                            fmt::format("{:.3f} .. {:.3f}", s.ratio.low, s.ratio.high)});
  std::vector<PageSection> sections{
      {"Stages per scene",
       "For each scene of the suite, whether its state needs clipping (a vertex outside a clip plane), depth (an "
       "attachment and the test on), bias (on, with a non-zero factor), MSAA, lines and culling. One row per scene "
       "in scene_needs.csv.",
       suite_needs.empty() ? std::vector<std::string>{} : std::vector<std::string>{"suite_needs"},
       stage_table},
      {"What a skipped stage saves",
       "The exact path with every work skip on, against the same render with one skip off (the work done anyway, "
       "same output), on timing scenes that do not need that stage; " +
           std::to_string(repeats) +
           " interleaved repetitions, the median ratio with its order-statistics 95% interval. Above 1: the skip "
           "saves time. MSAA, lines and culling have no work to skip when absent.",
       {"skip_savings"},
       saving_table}};
  write_index_html(options.out_dir, "Model no more than a scene needs", sections,
                   {kSceneNeedsCsv, kSkipSavingsCsv, "scene_needs.json"});
}

}  // namespace rastercmp::experiments
