#include "experiments/speed_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>

#include "experiments/csv_log.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/order_stats.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/scene_make.hpp"
#include "model/errors.hpp"

namespace rastercmp::experiments {
namespace {

using Clock = std::chrono::steady_clock;

Scene with_format(Scene scene, const std::optional<DepthFormat>& format) {
  if (format) scene.depth_format = *format;
  return scene;
}

// One entry of a set in the round robin: its scenes (formatted), its last results, its times.
struct Runner {
  std::string family, method;
  std::optional<CpuOptions> cpu;  // none: lavapipe
  std::vector<Scene> scenes;
  std::vector<std::unique_ptr<VulkanRenderer::Prepared>> prepared;  // lavapipe only
  std::vector<RenderResult> results;                                // last render of each scene
  std::vector<std::vector<double>> seconds;                         // [scene][repetition]
};

double time_once(VulkanRenderer& vk, Runner& r, size_t scene) {
  if (!r.cpu) return vk.submit_and_wait_seconds(*r.prepared[scene]);
  r.results[scene] = RenderResult{};  // the previous render's buffers are freed before the clock starts
  const auto start = Clock::now();
  r.results[scene] = render_cpu(r.scenes[scene], *r.cpu);
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<std::string> csv_row(const Runner& r, size_t scene, const Mismatch& m) {
  const MedianCi ci = median_ci(r.seconds[scene]);
  return {r.family,
          r.method,
          r.scenes[scene].name,
          to_string(r.scenes[scene].depth_format),
          num(ci.median),
          num(ci.low),
          num(ci.high),
          num(100.0 * double(m.coverage) / double(m.samples)),
          num(100.0 * double(m.depth) / double(m.samples)),
          num(double(m.samples))};
}

// Times every runner of one scene set, interleaved, and appends its CSV rows.
SceneSetRun run_set(VulkanRenderer& vk, const std::string& name, std::vector<Runner>& runners, int repeats,
                    CsvAppender& csv, Progress& progress) {
  const size_t scenes = runners.front().scenes.size();
  for (int rep = 0; rep < repeats; ++rep)
    for (size_t s = 0; s < scenes; ++s)
      for (size_t k = 0; k < runners.size(); ++k) {
        Runner& r = runners[(k + size_t(rep)) % runners.size()];  // the order rotates per repetition
        r.seconds[s].push_back(time_once(vk, r, s));
      }
  SceneSetRun run{name, {}, {}};
  for (Runner& r : runners) {
    std::vector<double> totals(size_t(repeats), 0.0);
    size_t coverage = 0, depth = 0, samples = 0;
    for (size_t s = 0; s < scenes; ++s) {
      for (int rep = 0; rep < repeats; ++rep) totals[size_t(rep)] += r.seconds[s][size_t(rep)];
      Mismatch m{0, 0, r.results[s].owner.size()};
      if (r.cpu) m = compare_results(r.results[s], vk.render(r.scenes[s]));
      coverage += m.coverage;
      depth += m.depth;
      samples += m.samples;
      csv.append(csv_row(r, s, m));
      progress.finished();
    }
    const MedianCi ci = median_ci(totals);
    EntrySummary e{r.family,
                   r.method,
                   ci.median,
                   samples ? 100.0 * double(coverage) / double(samples) : 0.0,
                   samples ? 100.0 * double(depth) / double(samples) : 0.0,
                   ci.low,
                   ci.high,
                   ci.coverage};
    if (r.cpu)
      run.entries.push_back(e);
    else
      run.lavapipe = e;
  }
  return run;
}

// The runners of one set: lavapipe first, then every entry that can run on all of the set's scenes
// (the first, untimed render of each scene also warms the caches).
std::vector<Runner> runners_for(VulkanRenderer& vk, const std::vector<MethodEntry>& entries, bool lines) {
  const std::vector<Scene> base = speed_accuracy_scenes(lines);
  std::vector<Runner> runners;
  Runner lavapipe{"reference", "lavapipe", std::nullopt, base, {}, {}, {}};
  for (const Scene& scene : base) {
    lavapipe.prepared.push_back(vk.prepare(scene));
    vk.submit_and_wait_seconds(*lavapipe.prepared.back());
    lavapipe.results.push_back(vk.read_back(*lavapipe.prepared.back()));
  }
  runners.push_back(std::move(lavapipe));
  for (const MethodEntry& entry : entries) {
    if (entry.lines != lines) continue;
    Runner r{entry.family, entry.method, entry.cpu, {}, {}, {}, {}};
    try {
      for (const Scene& scene : base) {
        r.scenes.push_back(with_format(scene, entry.depth_format));
        r.results.push_back(render_cpu(r.scenes.back(), entry.cpu));
      }
    } catch (const NotSupportedError&) {  // e.g. painter on a scene with lines: not in this set
      continue;
    }
    runners.push_back(std::move(r));
  }
  for (Runner& r : runners) r.seconds.assign(base.size(), {});
  return runners;
}

}  // namespace

std::vector<MethodEntry> speed_accuracy_entries() {
  std::vector<MethodEntry> entries;
  const CpuOptions exact = exact_cpu_options();
  entries.push_back({"exact path", "exact", exact, std::nullopt});
  CpuOptions no_fma = exact;
  no_fma.fma = false;
  entries.push_back({"exact path", "exact fma=off", no_fma, std::nullopt});
  for (uint32_t threads : {1u, 2u}) {
    CpuOptions fast = exact;
    fast.threads = threads;
    entries.push_back({"fast path", "threads=" + std::to_string(threads), fast, std::nullopt});
  }
  CpuOptions snap = exact;
  snap.methods = {{"snap", "round_half_away"}};
  entries.push_back({"set-up", "snap=round_half_away", snap, std::nullopt});
  CpuOptions tie = exact;
  tie.methods = {{"tie_break", "none"}};
  entries.push_back({"fill", "tie_break=none", tie, std::nullopt});
  for (DepthFormat format : sweep_depth_formats())
    entries.push_back({"depth format", to_string(format), exact, format});
  // The classic methods (cpu_raster/classic/, docs/methods.md), one stage swapped at a time.
  const struct {
    const char* family;
    const char* stage;
    const char* name;
  } classic[] = {
      {"clipping", "clip", "sutherland_hodgman"},
      {"fill", "fill", "scanline"},
      {"fill", "fill", "float_edge"},
      {"fill", "fill", "even_odd"},
      {"fill", "fill", "winding"},
      {"depth interpolation", "depth", "bilinear"},
      {"depth interpolation", "depth", "perspective_correct"},
      {"visibility", "visibility", "painter"},
      {"visibility", "visibility", "bsp"},
      {"culling", "cull", "normal_dot_view"},
  };
  for (const auto& c : classic) {
    CpuOptions options = exact;
    options.methods = {{c.stage, c.name}};
    entries.push_back({c.family, std::string(c.stage) + "=" + c.name, options, std::nullopt});
  }
  // The line set: the exact path and its fast path on lines, against the notes' DDA and Bresenham.
  entries.push_back({"exact path", "exact", exact, std::nullopt, true});
  CpuOptions fast_lines = exact;
  fast_lines.threads = 2;
  entries.push_back({"fast path", "threads=2", fast_lines, std::nullopt, true});
  for (const char* name : {"dda", "bresenham"}) {
    CpuOptions options = exact;
    options.methods = {{"line", name}};
    entries.push_back({"line", std::string("line=") + name, options, std::nullopt, true});
  }
  return entries;
}

std::vector<Scene> speed_accuracy_scenes(bool lines) {
  if (lines) return {make_line_star(256, 64)};
  std::vector<Scene> set;
  PairParams pair;
  pair.angle_deg = 45;
  pair.format = DepthFormat::D32Sfloat;
  set.push_back(make_decal_scene(pair).scene);
  PairParams house;
  house.kind = PairKind::House;
  house.far_near_ratio = 3;  // the notes' near 25, far 75
  house.decal_bias.enable = true;
  house.decal_bias.constant_factor = -2;  // scenes/house/far_75.json
  house.decal_bias.slope_factor = -1;
  set.push_back(make_decal_scene(house).scene);
  set.push_back(make_sliver_pair(1.0, 60));
  set.push_back(make_mesh_scene(256, 24));
  return set;
}

std::vector<std::pair<std::string, std::vector<size_t>>> family_pareto_fronts(const std::vector<EntrySummary>& entries,
                                                                               bool coverage) {
  const auto shared = [](const std::string& family) { return family == "exact path" || family == "fast path"; };
  std::vector<std::pair<std::string, std::vector<size_t>>> out;
  for (const EntrySummary& e : entries) {
    if (shared(e.family)) continue;
    bool seen = false;
    for (const auto& f : out) seen = seen || f.first == e.family;
    if (seen) continue;
    std::vector<size_t> members;
    for (size_t i = 0; i < entries.size(); ++i)
      if (entries[i].family == e.family || shared(entries[i].family)) members.push_back(i);
    std::vector<EntrySummary> subset;
    for (size_t i : members) subset.push_back(entries[i]);
    std::vector<size_t> front;
    for (size_t j : pareto_front(subset, coverage)) front.push_back(members[j]);
    out.push_back({e.family, front});
  }
  return out;
}

std::vector<size_t> pareto_front(const std::vector<EntrySummary>& entries, bool coverage) {
  std::vector<size_t> order(entries.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto miss = [&](size_t i) {
    return coverage ? entries[i].coverage_mismatch_pct : entries[i].depth_mismatch_pct;
  };
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return entries[a].seconds_per_frame != entries[b].seconds_per_frame
               ? entries[a].seconds_per_frame < entries[b].seconds_per_frame
               : miss(a) < miss(b);
  });
  std::vector<size_t> front;
  for (size_t i : order)
    if (front.empty() || miss(i) < miss(front.back())) front.push_back(i);
  return front;
}

void run_speed_accuracy(const SweepOptions& options) {
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  VulkanRenderer vk(VkOptions{});
  SpeedAccuracyRun run;
  run.repeats = options.quick ? 5 : 21;
  const std::vector<MethodEntry> entries = speed_accuracy_entries();
  CsvAppender csv((std::filesystem::path(options.out_dir) / kSpeedAccuracyCsv).string(),
                  {"family", "method", "scene", "format", "seconds_per_frame", "seconds_ci_low", "seconds_ci_high",
                   "coverage_mismatch_pct", "depth_mismatch_pct", "samples"},
                  4, false);
  std::vector<Runner> triangles = runners_for(vk, entries, false), lines = runners_for(vk, entries, true);
  Progress progress("chart speed-accuracy", triangles.size() * triangles.front().scenes.size() +
                                                lines.size() * lines.front().scenes.size());
  run.sets.push_back(run_set(vk, "triangles", triangles, run.repeats, csv, progress));
  run.sets.push_back(run_set(vk, "lines", lines, run.repeats, csv, progress));
  progress.done();
  write_speed_accuracy_outputs(options.out_dir, run);
}

}  // namespace rastercmp::experiments
