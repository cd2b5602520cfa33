#include "experiments/speed_accuracy.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>

#include "experiments/csv_log.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/scene_make.hpp"
#include "model/errors.hpp"

namespace rastercmp::experiments {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

std::vector<Scene> scene_set() {
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

Scene with_format(Scene scene, const std::optional<DepthFormat>& format) {
  if (format) scene.depth_format = *format;
  return scene;
}

double time_cpu(const Scene& scene, const CpuOptions& cpu, int repeats, RenderResult& result) {
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) {
    const auto start = std::chrono::steady_clock::now();
    result = render_cpu(scene, cpu);
    times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return median(times);
}

double time_vk(VulkanRenderer& vk, const Scene& scene, int repeats, RenderResult& result) {
  std::unique_ptr<VulkanRenderer::Prepared> prepared = vk.prepare(scene);
  std::vector<double> times;
  for (int i = 0; i < repeats; ++i) times.push_back(vk.submit_and_wait_seconds(*prepared));
  result = vk.read_back(*prepared);
  return median(times);
}

struct Totals {
  double seconds = 0;
  size_t coverage = 0, depth = 0, samples = 0;
  EntrySummary summary(const std::string& family, const std::string& method) const {
    return {family, method, seconds, samples ? 100.0 * double(coverage) / double(samples) : 0.0,
            samples ? 100.0 * double(depth) / double(samples) : 0.0};
  }
};

std::vector<std::string> csv_row(const std::string& family, const std::string& method, const Scene& scene,
                                 double seconds, const Mismatch& m) {
  return {family,
          method,
          scene.name,
          to_string(scene.depth_format),
          num(seconds),
          num(100.0 * double(m.coverage) / double(m.samples)),
          num(100.0 * double(m.depth) / double(m.samples)),
          num(double(m.samples))};
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
  return entries;
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
  const int repeats = options.quick ? 3 : 15;
  const std::vector<Scene> scenes = scene_set();
  const std::vector<MethodEntry> entries = speed_accuracy_entries();
  CsvAppender csv((std::filesystem::path(options.out_dir) / kSpeedAccuracyCsv).string(),
                  {"family", "method", "scene", "format", "seconds_per_frame", "coverage_mismatch_pct",
                   "depth_mismatch_pct", "samples"},
                  4, false);
  Progress progress("chart speed-accuracy", (entries.size() + 1) * scenes.size());
  SpeedAccuracyRun run;
  Totals lavapipe;
  for (const Scene& scene : scenes) {
    RenderResult ref;
    const double seconds = time_vk(vk, scene, repeats, ref);
    lavapipe.seconds += seconds;
    lavapipe.samples += ref.owner.size();
    csv.append(csv_row("reference", "lavapipe", scene, seconds, Mismatch{0, 0, ref.owner.size()}));
    progress.finished();
  }
  run.lavapipe = lavapipe.summary("reference", "lavapipe");
  for (const MethodEntry& entry : entries) {
    Totals totals;
    for (const Scene& base : scenes) {
      const Scene scene = with_format(base, entry.depth_format);
      RenderResult cpu, ref;
      double seconds = 0;
      try {
        seconds = time_cpu(scene, entry.cpu, repeats, cpu);
      } catch (const NotSupportedError&) {  // e.g. painter on a scene with lines: not on the chart
        progress.finished();
        continue;
      }
      time_vk(vk, scene, 1, ref);
      const Mismatch m = compare_results(cpu, ref);
      totals.seconds += seconds;
      totals.coverage += m.coverage;
      totals.depth += m.depth;
      totals.samples += m.samples;
      csv.append(csv_row(entry.family, entry.method, scene, seconds, m));
      progress.finished();
    }
    run.entries.push_back(totals.summary(entry.family, entry.method));
  }
  progress.done();
  write_speed_accuracy_outputs(options.out_dir, run);
}

}  // namespace rastercmp::experiments
