#include "experiments/speed_accuracy.hpp"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "experiments/csv_log.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/order_stats.hpp"
#include "experiments/pixel_stats.hpp"
#include "experiments/progress.hpp"
#include "experiments/scene_make.hpp"
#include "model/camera.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"

namespace rastercmp::experiments {
namespace {

using Clock = std::chrono::steady_clock;

double cpu_clock_seconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

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
  std::vector<std::vector<double>> seconds, cpu_seconds;            // [scene][repetition]
};

Tier tier_of(const Runner& r) { return !r.cpu ? Tier::Reference : r.cpu->threads == 0 ? Tier::Scalar : Tier::Fast; }

// A scalar render runs on the calling thread alone, so that thread's clock is its CPU time; the
// fast path's and lavapipe's work runs on worker threads, which only the process clock sees.
clockid_t cpu_clock_of(const Runner& r) {
  return tier_of(r) == Tier::Scalar ? CLOCK_THREAD_CPUTIME_ID : CLOCK_PROCESS_CPUTIME_ID;
}

struct Timing {
  double wall = 0, cpu = 0;
};

Timing time_once(VulkanRenderer& vk, Runner& r, size_t scene) {
  const clockid_t clock = cpu_clock_of(r);
  if (!r.cpu) {
    const double cpu_start = cpu_clock_seconds(clock);
    const double wall = vk.submit_and_wait_seconds(*r.prepared[scene]);
    return {wall, cpu_clock_seconds(clock) - cpu_start};
  }
  r.results[scene] = RenderResult{};  // the previous render's buffers are freed before the clock starts
  const double cpu_start = cpu_clock_seconds(clock);
  const auto start = Clock::now();
  r.results[scene] = render_cpu(r.scenes[scene], *r.cpu);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  return {wall, cpu_clock_seconds(clock) - cpu_start};
}

std::vector<std::string> csv_row(const Runner& r, size_t scene, const Mismatch& m) {
  const MedianCi ci = median_ci(r.seconds[scene]), cpu = median_ci(r.cpu_seconds[scene]);
  return {r.family,
          r.method,
          to_string(tier_of(r)),
          r.scenes[scene].name,
          to_string(r.scenes[scene].depth_format),
          num(ci.median),
          num(ci.low),
          num(ci.high),
          num(run_spread(r.seconds[scene])),
          num(cpu.median),
          tier_of(r) == Tier::Scalar ? "thread" : "process",
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
        const Timing t = time_once(vk, r, s);
        r.seconds[s].push_back(t.wall);
        r.cpu_seconds[s].push_back(t.cpu);
      }
  SceneSetRun run{name, {}, {}, {}};
  for (Runner& r : runners) {
    EntrySummary e;
    e.family = r.family;
    e.method = r.method;
    e.tier = tier_of(r);
    e.cpu_clock = e.tier == Tier::Scalar ? "thread" : "process";
    e.wall_runs.assign(size_t(repeats), 0.0);
    e.cpu_runs.assign(size_t(repeats), 0.0);
    size_t coverage = 0, depth = 0, samples = 0;
    for (size_t s = 0; s < scenes; ++s) {
      for (size_t rep = 0; rep < size_t(repeats); ++rep) {
        e.wall_runs[rep] += r.seconds[s][rep];
        e.cpu_runs[rep] += r.cpu_seconds[s][rep];
      }
      Mismatch m{0, 0, r.results[s].owner.size()};
      if (r.cpu) m = compare_results(r.results[s], vk.render(r.scenes[s]));
      coverage += m.coverage;
      depth += m.depth;
      samples += m.samples;
      csv.append(csv_row(r, s, m));
      progress.finished();
    }
    const MedianCi wall = median_ci(e.wall_runs), cpu = median_ci(e.cpu_runs);
    e.seconds_per_frame = wall.median;
    e.seconds_low = wall.low;
    e.seconds_high = wall.high;
    e.ci_coverage = wall.coverage;
    e.cpu_seconds = cpu.median;
    e.cpu_seconds_low = cpu.low;
    e.cpu_seconds_high = cpu.high;
    e.coverage_mismatch_pct = samples ? 100.0 * double(coverage) / double(samples) : 0.0;
    e.depth_mismatch_pct = samples ? 100.0 * double(depth) / double(samples) : 0.0;
    if (r.cpu)
      run.entries.push_back(std::move(e));
    else
      run.lavapipe = std::move(e);
  }
  return run;
}

// The runners of one set: lavapipe first, then every entry that can run on all of the set's scenes
// (the first, untimed render of each scene also warms the caches). An entry that refuses a scene
// is left out of the set, with the reason in `left_out`, so that its absence is visible.
std::vector<Runner> runners_for(VulkanRenderer& vk, const std::vector<MethodEntry>& entries, bool lines,
                                std::vector<std::pair<std::string, std::string>>& left_out) {
  const std::vector<Scene> base = speed_accuracy_scenes(lines);
  std::vector<Runner> runners;
  Runner lavapipe{"reference", "lavapipe", std::nullopt, base, {}, {}, {}, {}};
  for (const Scene& scene : base) {
    lavapipe.prepared.push_back(vk.prepare(scene));
    vk.submit_and_wait_seconds(*lavapipe.prepared.back());
    lavapipe.results.push_back(vk.read_back(*lavapipe.prepared.back()));
  }
  runners.push_back(std::move(lavapipe));
  for (const MethodEntry& entry : entries) {
    if (entry.lines != lines) continue;
    Runner r{entry.family, entry.method, entry.cpu, {}, {}, {}, {}, {}};
    try {
      for (const Scene& scene : base) {
        r.scenes.push_back(with_format(scene, entry.depth_format));
        r.results.push_back(render_cpu(r.scenes.back(), entry.cpu));
      }
    } catch (const NotSupportedError& e) {  // e.g. painter on a scene with lines: not in this set
      left_out.push_back({entry.family + ": " + entry.method, r.scenes.back().name + ": " + e.what()});
      continue;
    }
    runners.push_back(std::move(r));
  }
  for (Runner& r : runners) {
    r.seconds.assign(base.size(), {});
    r.cpu_seconds.assign(base.size(), {});
  }
  return runners;
}

double load_average_1min() {
  double load[1];
  return getloadavg(load, 1) == 1 ? load[0] : -1;
}

std::string host_name() {
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0 || name[0] == 0) return "unknown";
  return name.data();
}

// `git -C DIR ARGS` and its first output line; empty when git or the checkout is not there.
std::string git_line(const std::string& dir, const std::string& args) {
  std::string quoted = "'";
  for (char c : dir) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  quoted += "'";
  std::FILE* pipe = ::popen(("git -C " + quoted + " " + args + " 2>/dev/null").c_str(), "r");
  if (!pipe) return "";
  std::string out;
  char buffer[256];
  while (std::fgets(buffer, sizeof buffer, pipe)) out += buffer;
  const int status = ::pclose(pipe);
  if (status != 0) return "";
  return out.substr(0, out.find('\n'));
}

// The checkout the binary was built in (it lives in its build tree), else the working directory:
// the commit the measured code came from.
void fill_git(RunHost& host) {
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  for (const std::string& dir : {error ? std::string() : exe.parent_path().string(), std::string(".")}) {
    if (dir.empty()) continue;
    std::string commit = git_line(dir, "rev-parse HEAD");
    if (commit.empty()) continue;
    host.git_commit = commit;
    host.git_dirty = !git_line(dir, "status --porcelain --untracked-files=no").empty();
    return;
  }
}

}  // namespace

RunHost current_run_host() {
  RunHost host;
  host.host = host_name();
  host.cpu_model = host_cpu_model();
  fill_git(host);
  return host;
}

double run_load_average() { return load_average_1min(); }

const char* to_string(Tier tier) {
  switch (tier) {
    case Tier::Scalar: return "scalar";
    case Tier::Fast: return "fast";
    case Tier::Reference: return "reference";
  }
  return "?";
}

const char* to_string(FrontClock clock) { return clock == FrontClock::Cpu ? "cpu" : "wall"; }

EntrySummary timed_by(const EntrySummary& e, FrontClock clock) {
  EntrySummary out = e;
  if (clock == FrontClock::Wall) return out;
  out.seconds_per_frame = e.cpu_seconds;
  out.seconds_low = e.cpu_seconds_low;
  out.seconds_high = e.cpu_seconds_high;
  out.wall_runs = e.cpu_runs;
  return out;
}

double run_spread(const std::vector<double>& values) {
  if (values.empty()) return 0;
  const double median = median_ci(values).median;
  if (!(median > 0)) return 0;
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  return (*high - *low) / median;
}

std::vector<MethodEntry> speed_accuracy_entries() {
  std::vector<MethodEntry> entries;
  const CpuOptions exact = exact_cpu_options();
  entries.push_back({"exact path", "exact", exact, std::nullopt});
  CpuOptions no_fma = exact;
  no_fma.fma = false;
  // Whole-path FMA off changes the depth plane alone: it sits with the depth methods (depth=no_fma
  // is the same rounding as a classic method), so that the exact path is the one baseline of every family.
  entries.push_back({"depth interpolation", "exact fma=off", no_fma, std::nullopt});
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
  // The classic methods (cpu_raster/classic/, docs/methods.md), one stage swapped at a time; every
  // method of `rastercmp methods` that draws triangles.
  struct Classic {
    const char* family;
    const char* stage;
    const char* name;
  };
  const Classic classic[] = {
      {"clipping", "clip", "sutherland_hodgman"},
      {"clipping", "clip", "weiler_atherton"},
      {"fill", "fill", "scanline"},
      {"fill", "fill", "float_edge"},
      {"fill", "fill", "even_odd"},
      {"fill", "fill", "winding"},
      {"fill", "fill", "flood"},
      {"depth interpolation", "depth", "no_fma"},
      {"depth interpolation", "depth", "bilinear"},
      {"depth interpolation", "depth", "perspective_correct"},
      {"depth interpolation", "depth", "pseudo_depth_75"},
      {"depth interpolation", "depth", "pseudo_depth_750"},
      {"depth interpolation", "depth", "pseudo_depth_7500"},
      {"visibility", "visibility", "painter"},
      {"visibility", "visibility", "bsp"},
      {"culling", "cull", "normal_dot_view"},
  };
  const auto add_classic = [&](const Classic& c, bool lines) {
    CpuOptions options = exact;
    options.methods = {{c.stage, c.name}};
    entries.push_back({c.family, std::string(c.stage) + "=" + c.name, options, std::nullopt, lines});
  };
  for (const Classic& c : classic) add_classic(c, false);
  // The line set: the exact path and its fast path on lines, against the notes' DDA and Bresenham
  // and the line clippers (the set's second scene crosses the viewport's edges).
  entries.push_back({"exact path", "exact", exact, std::nullopt, true});
  CpuOptions fast_lines = exact;
  fast_lines.threads = 2;
  entries.push_back({"fast path", "threads=2", fast_lines, std::nullopt, true});
  const Classic line_methods[] = {
      {"line", "line", "dda"},
      {"line", "line", "bresenham"},
      {"line clipping", "clip", "cohen_sutherland"},
      {"line clipping", "clip", "cohen_sutherland_3d"},
      {"line clipping", "clip", "liang_barsky"},
      {"line clipping", "clip", "cyrus_beck"},
  };
  for (const Classic& c : line_methods) add_classic(c, true);
  return entries;
}

Scene make_clipped_lines(uint32_t size, uint32_t lines) {
  Scene scene;
  scene.name = "experiments.clipped_lines";
  scene.width = scene.height = size;
  const Viewport viewport = scene.effective_viewport();
  Draw draw;
  draw.topology = Topology::LineList;
  const double centre = size / 2.0 + 0.3;
  for (uint32_t i = 0; i < lines; ++i) {
    const double a = 2 * std::numbers::pi * (i + 0.37) / lines;
    const double z0 = 0.2 + 0.6 * double(i % 7) / 6, z1 = 0.8 - 0.6 * double(i % 5) / 4;
    glm::dvec2 from, to;
    if (i % 4 == 3) {  // a chord through the frame: both ends outside, two edges crossed
      const glm::dvec2 d(std::cos(a), std::sin(a)), n(-d.y, d.x);
      const double offset = size * (0.3 * double(i % 8) / 8 - 0.1);
      from = glm::dvec2(centre) + n * offset - d * (size * 0.9);
      to = glm::dvec2(centre) + n * offset + d * (size * 0.9);
    } else if (i % 8 == 5) {  // wholly outside, beside the frame: rejected by every clipper
      const glm::dvec2 d(std::cos(a), std::sin(a));
      from = glm::dvec2(centre) + d * (size * 0.8);
      to = glm::dvec2(centre) + d * (size * 1.1) + glm::dvec2(-d.y, d.x) * (size * 0.1);
    } else {  // from inside the frame to outside it: one edge crossed
      from = glm::dvec2(centre) + glm::dvec2(std::cos(a), std::sin(a)) * (size * 0.1);
      to = glm::dvec2(centre) + glm::dvec2(std::cos(a), std::sin(a)) * (size * (0.6 + 0.1 * double(i % 3)));
    }
    draw.positions_clip.push_back(pixels_to_clip(viewport, glm::vec4(float(from.x), float(from.y), float(z0), 1)));
    draw.positions_clip.push_back(pixels_to_clip(viewport, glm::vec4(float(to.x), float(to.y), float(z1), 1)));
  }
  scene.draws.push_back(draw);
  return scene;
}

// The sliver pair and the mesh are made at w = 1 (pixels_to_clip). Scaling a clip position by w
// keeps its window position (x/w, y/w, z/w) and puts it at eye distance w; at 50 every scene of the
// set lies between the notes' pseudo-depth near 25 and far 75, so the pseudo-depth methods run on
// the whole set. Both backends get the same scaled positions.
namespace {
Scene at_eye_distance(Scene scene, float w) {
  for (Draw& draw : scene.draws)
    for (glm::vec4& p : draw.positions_clip) p *= w / p.w;
  return scene;
}
}  // namespace

std::vector<Scene> speed_accuracy_scenes(bool lines) {
  if (lines) return {make_line_star(256, 64), make_clipped_lines(256, 64)};
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
  set.push_back(at_eye_distance(make_sliver_pair(1.0, 60), 50));
  set.push_back(at_eye_distance(make_mesh_scene(256, 24), 50));
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

std::vector<FrontPoint> mark_separation(const std::vector<EntrySummary>& entries, const std::vector<size_t>& front,
                                        const std::vector<size_t>& candidates, bool coverage) {
  const auto overlap = [&](size_t a, size_t b) {
    return entries[a].seconds_low <= entries[b].seconds_high && entries[b].seconds_low <= entries[a].seconds_high;
  };
  const auto miss = [&](size_t i) {
    return coverage ? entries[i].coverage_mismatch_pct : entries[i].depth_mismatch_pct;
  };
  std::vector<FrontPoint> points;
  for (size_t k = 0; k < front.size(); ++k) {
    bool separated =
        !(k > 0 && overlap(front[k], front[k - 1])) && !(k + 1 < front.size() && overlap(front[k], front[k + 1]));
    for (size_t c : candidates)
      if (std::find(front.begin(), front.end(), c) == front.end() && miss(c) == miss(front[k]) && overlap(c, front[k]))
        separated = false;
    points.push_back({front[k], separated});
  }
  return points;
}

std::vector<std::string> scalar_families(const std::vector<EntrySummary>& entries) {
  std::vector<std::string> families;
  for (const EntrySummary& e : entries)
    if (e.tier == Tier::Scalar && e.family != "exact path" &&
        std::find(families.begin(), families.end(), e.family) == families.end())
      families.push_back(e.family);
  return families;
}

std::vector<FrontPoint> scalar_front(const std::vector<EntrySummary>& entries, const std::string& family,
                                     bool coverage) {
  std::vector<size_t> members;
  for (size_t i = 0; i < entries.size(); ++i)
    if (entries[i].tier == Tier::Scalar &&
        (family.empty() || entries[i].family == family || entries[i].family == "exact path"))
      members.push_back(i);
  std::vector<EntrySummary> subset;
  for (size_t i : members) subset.push_back(entries[i]);
  std::vector<size_t> front;
  for (size_t j : pareto_front(subset, coverage)) front.push_back(members[j]);
  return mark_separation(entries, front, members, coverage);
}

void run_speed_accuracy(const SweepOptions& options, int repetitions, FrontClock clock) {
  if (repetitions < 0) throw std::invalid_argument("speed-accuracy: the repetitions must be at least 1");
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  VulkanRenderer vk(VkOptions{});
  SpeedAccuracyRun run;
  run.repeats = repetitions > 0 ? repetitions : options.quick ? 5 : 21;
  run.clock = clock;
  run.host.host = host_name();
  run.host.cpu_model = host_cpu_model();
  fill_git(run.host);
  run.host.freed_memory_kept = options.freed_memory_kept;
  const std::vector<MethodEntry> entries = speed_accuracy_entries();
  CsvAppender csv((std::filesystem::path(options.out_dir) / kSpeedAccuracyCsv).string(),
                  {"family", "method", "tier", "scene", "format", "seconds_per_frame", "seconds_ci_low",
                   "seconds_ci_high", "seconds_spread", "cpu_seconds_per_frame", "cpu_clock", "coverage_mismatch_pct",
                   "depth_mismatch_pct", "samples"},
                  5, false);
  std::vector<std::pair<std::string, std::string>> left_triangles, left_lines;
  std::vector<Runner> triangles = runners_for(vk, entries, false, left_triangles),
                      lines = runners_for(vk, entries, true, left_lines);
  Progress progress("chart speed-accuracy",
                    triangles.size() * triangles.front().scenes.size() + lines.size() * lines.front().scenes.size());
  run.host.load_before = load_average_1min();
  run.sets.push_back(run_set(vk, "triangles", triangles, run.repeats, csv, progress));
  run.sets.back().left_out = left_triangles;
  run.sets.push_back(run_set(vk, "lines", lines, run.repeats, csv, progress));
  run.sets.back().left_out = left_lines;
  run.host.load_after = load_average_1min();
  progress.done();
  write_speed_accuracy_outputs(options.out_dir, run);
}

}  // namespace rastercmp::experiments
