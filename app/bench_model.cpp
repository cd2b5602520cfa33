// rastercmp bench --scaling --model [--tasks N]: the fast path on 1, 2, 4, ..., 64 workers, each
// worker's and queued task's thread CPU time per phase projected onto as many free cores
// (docs/performance.md, "Scaling model").
#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory_resource>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/bench_common.hpp"
#include "app/options.hpp"
#include "bench/bench_stats.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/fast/render_fast.hpp"
#include "experiments/gnuplot.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/render_result.hpp"

namespace rastercmp::app {

const std::vector<uint32_t> kModelWorkers = {1, 2, 4, 8, 16, 32, 64};

namespace {

// --scaling --model: a model of the fast path on N cores, measured on the cores there are. Each
// render runs with N workers (as render_cpu_fast does: a small scene takes one worker), their jobs
// run by at most the CPUs it may use one after another (FastConfig::profile_threads), and
// records each worker's thread CPU time per phase and each queue task's (RenderProfile); on N free
// cores a phase would take projected_seconds (its busiest worker; a queue phase: its tasks handed
// in order to the first worker free), so the projected render time is the calling thread's serial
// time plus that per phase. The reps take every N in turn (rep 1 at N = 1, 2, ..., 64, then rep 2,
// ...), so that a host whose speed drifts between states over seconds (a shared VM) moves every N
// alike, and each scene's profile at N is the median of its reps' (median_profile: each task's and
// each worker's time the median of the reps'), so that a task the host held up in one rep does not
// set its phase. The projected speed-up at N is projected(1) / projected(N). What it leaves out:
// waking the workers, memory bandwidth and caches shared by N cores. Checked against the measured
// wall time where N <= the CPUs it may use (host_usable_cpus: `taskset -c 0,1` on a larger host
// measures the two-core projection and times nothing past 2): the same renders again without a
// profile, right after the profiled ones (a profiled render also pays the clock readings the
// projection leaves out, two a queued task: about 0.1 ms of perspective's at two workers).
//
// The reps' profiles are kept out of the heap the renders allocate from (ProfileStore), and every
// ModelRep is sized before the first render: a profile kept in that heap between renders takes
// the memory a render freed, so the next render's arrays come from pages never touched, and a
// first touch cost 10-35 us on the Zen 5 host (2-5 faults in a third of perspective's renders at
// two workers, 50-160 us more of its serial part; docs/performance-log.md, "Page faults in the
// model's profiled renders"). Each render is profiled into one reused RenderProfile, copied into
// the store after it; the page faults during the profiled renders are counted and printed.

// Pages from mmap, outside malloc's heap, given back when the store goes.
class MappedResource : public std::pmr::memory_resource {
  void* do_allocate(size_t bytes, size_t) override {
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    return p;
  }
  void do_deallocate(void* p, size_t bytes, size_t) override { munmap(p, bytes); }
  bool do_is_equal(const std::pmr::memory_resource& other) const noexcept override { return this == &other; }
};

// A RenderProfile flattened into doubles in mapped memory: the serial time, the phase count, then
// per phase its name (an index into `names`), serial_before, its workers' times and its tasks'
// (seconds, worker).
struct StoredProfile {
  const double* data = nullptr;
};

class ProfileStore {
 public:
  ProfileStore() { names_.reserve(64); }

  StoredProfile store(const cpu::fast::RenderProfile& profile) {
    size_t size = 2;
    for (const cpu::fast::PhaseTimes& phase : profile.phases)
      size += 4 + phase.worker_seconds.size() + 2 * phase.tasks.size();
    auto* data = static_cast<double*>(arena_.allocate(size * sizeof(double), alignof(double)));
    size_t at = 0;
    data[at++] = profile.serial_seconds;
    data[at++] = double(profile.phases.size());
    for (const cpu::fast::PhaseTimes& phase : profile.phases) {
      data[at++] = double(name_index(phase.phase));
      data[at++] = phase.serial_before;
      data[at++] = double(phase.worker_seconds.size());
      for (const double t : phase.worker_seconds) data[at++] = t;
      data[at++] = double(phase.tasks.size());
      for (const cpu::fast::TaskTime& task : phase.tasks) {
        data[at++] = task.seconds;
        data[at++] = double(task.worker);
      }
    }
    return StoredProfile{data};
  }

  cpu::fast::RenderProfile load(const StoredProfile& stored) const {
    cpu::fast::RenderProfile profile;
    const double* d = stored.data;
    size_t at = 0;
    profile.serial_seconds = d[at++];
    profile.phases.resize(size_t(d[at++]));
    for (cpu::fast::PhaseTimes& phase : profile.phases) {
      phase.phase = names_[size_t(d[at++])];
      phase.serial_before = d[at++];
      phase.worker_seconds.resize(size_t(d[at++]));
      for (double& t : phase.worker_seconds) t = d[at++];
      phase.tasks.resize(size_t(d[at++]));
      for (cpu::fast::TaskTime& task : phase.tasks) {
        task.seconds = d[at++];
        task.worker = uint32_t(d[at++]);
      }
    }
    return profile;
  }

 private:
  // a phase's name, added the first time it is met (a handful: reserved, so no allocation after)
  size_t name_index(const std::string& name) {
    for (size_t i = 0; i < names_.size(); ++i)
      if (names_[i] == name) return i;
    names_.push_back(name);
    return names_.size() - 1;
  }

  MappedResource mapped_;
  std::pmr::monotonic_buffer_resource arena_{size_t(1) << 20, &mapped_};
  std::vector<std::string> names_;
};

struct ModelRep {
  double wall = 0;  // seconds per unprofiled render of the case (0 where not timed)
  long faults = 0;  // page faults during its profiled renders (bench::page_fault_count)
  // per scene (the case's order): its profile on N workers; a scene queued side by side: its
  // time on one worker (queued_seconds) instead
  std::vector<StoredProfile> profiles;
  std::vector<double> queued_seconds;
  std::vector<size_t> queue;  // the queued scenes in queue order (side_by_side_queue)
  std::vector<bool> in_queue;

  explicit ModelRep(size_t scenes) : profiles(scenes), queued_seconds(scenes, 0.0), in_queue(scenes, false) {
    queue.reserve(scenes);
  }
};

// What the renders of a rep reuse: the profile each is profiled into (one per scene side by side).
struct ModelScratch {
  cpu::fast::RenderProfile profile;
  std::vector<cpu::fast::RenderProfile> side_by_side;
};

struct ModelPoint {
  double projected = 0, wall = 0;                      // seconds per render of the case; wall: the median of the reps'
  double worker_spread = 0;                            // bands phase: projected / mean worker time (1 = even)
  std::vector<std::pair<std::string, double>> phases;  // per phase: its projection, summed over scenes
  std::vector<std::pair<std::string, cpu::fast::RenderProfile>> profiles;  // each scene's median profile
};

// The projection of queued scenes rendered side by side (render_fast_side_by_side) on `workers`
// free cores: each scene's time on one worker, in queue order (side_by_side_queue), to the first
// worker free.
double side_by_side_seconds(const std::vector<double>& scene_seconds, uint32_t workers) {
  std::vector<double> free(std::max(workers, 1u), 0.0);
  for (const double t : scene_seconds) *std::min_element(free.begin(), free.end()) += t;
  return *std::max_element(free.begin(), free.end());
}

// One rep of the case's scenes on `workers` workers into `rep` (sized for them), profiled, then
// (`timed`) timed unprofiled.
void model_rep(ModelRep& rep, ProfileStore& store, ModelScratch& scratch, std::vector<Scene>& scenes,
               std::vector<RenderResult>& results, CpuOptions options, uint32_t workers, bool side_by_side,
               bool timed) {
  options.threads = workers;
  cpu::fast::FastConfig config;
  config.profile_threads = host_usable_cpus();
  if (side_by_side) {
    const long faults = bench::page_fault_count();
    cpu::fast::render_fast_side_by_side(scenes, options, config, results, &scratch.side_by_side);
    rep.faults = bench::page_fault_count() - faults;
    for (size_t i = 0; i < scenes.size(); ++i) rep.profiles[i] = store.store(scratch.side_by_side[i]);
    const std::vector<size_t> queue = cpu::fast::side_by_side_queue(scenes, options, config);
    rep.queue.assign(queue.begin(), queue.end());
    for (const size_t i : rep.queue) {
      rep.in_queue[i] = true;
      rep.queued_seconds[i] = cpu::fast::projected_seconds(scratch.side_by_side[i]);
    }
    if (timed)
      rep.wall = seconds_of([&] { cpu::fast::render_fast_side_by_side(scenes, options, config, results, nullptr); });
    return;
  }
  for (size_t i = 0; i < scenes.size(); ++i) {
    config.profile = &scratch.profile;
    const long faults = bench::page_fault_count();
    cpu::fast::render_fast_into(scenes[i], options, config, results[i]);
    rep.faults += bench::page_fault_count() - faults;
    config.profile = nullptr;
    rep.profiles[i] = store.store(scratch.profile);
    if (timed) rep.wall += seconds_of([&] { cpu::fast::render_fast_into(scenes[i], options, config, results[i]); });
  }
}

// The point at N from its reps: each scene's median profile projected, the queued scenes' median
// times on one worker list-scheduled on N.
ModelPoint model_point(const std::vector<ModelRep>& reps, const ProfileStore& store, const std::vector<Scene>& scenes,
                       uint32_t workers) {
  ModelPoint point;
  std::vector<double> walls, queued;
  for (const ModelRep& rep : reps) walls.push_back(rep.wall);
  point.wall = bench::summarize(walls).median;
  point.phases = {{"serial", 0.0}};
  double busiest_bands = 0, mean_bands = 0;
  for (size_t i = 0; i < scenes.size(); ++i) {
    if (reps.front().in_queue[i]) continue;
    std::vector<cpu::fast::RenderProfile> of_scene;
    for (const ModelRep& rep : reps) of_scene.push_back(store.load(rep.profiles[i]));
    const cpu::fast::RenderProfile profile = cpu::fast::median_profile(of_scene);
    point.projected += profile.serial_seconds;
    point.phases.front().second += profile.serial_seconds;
    for (const cpu::fast::PhaseTimes& phase : profile.phases) {
      const double busiest = cpu::fast::projected_seconds(phase);
      point.projected += busiest;
      auto it =
          std::find_if(point.phases.begin(), point.phases.end(), [&](const auto& p) { return p.first == phase.phase; });
      if (it == point.phases.end()) it = point.phases.insert(point.phases.end(), {phase.phase, 0.0});
      it->second += busiest;
      if (phase.phase == "bands") {
        busiest_bands += busiest;
        double sum = 0;
        for (double t : phase.worker_seconds) sum += t;
        for (const cpu::fast::TaskTime& task : phase.tasks) sum += task.seconds;
        mean_bands += sum / double(phase.worker_seconds.size());
      }
    }
    point.profiles.emplace_back(scenes[i].name, profile);
  }
  for (const size_t i : reps.front().queue) {  // in queue order
    std::vector<double> times;
    for (const ModelRep& rep : reps) times.push_back(rep.queued_seconds[i]);
    queued.push_back(bench::summarize(times).median);
  }
  if (!queued.empty()) {
    const double side = side_by_side_seconds(queued, workers);
    point.projected += side;
    point.phases.emplace_back("side by side", side);
  }
  point.worker_spread = mean_bands > 0 ? busiest_bands / mean_bands : 1.0;
  return point;
}

// --tasks: each queue phase of each scene at N workers (its median profile), its tasks' count,
// their CPU time summed, the largest and every task's time in queue order (the times the list
// scheduling of projected_seconds hands out; in the JSON with the worker it hands each to): a
// line each appended to `text`, and as JSON.
nlohmann::ordered_json describe_tasks(const ModelPoint& point, uint32_t workers, std::string& text) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [scene, profile] : point.profiles) {
    for (const cpu::fast::PhaseTimes& phase : profile.phases) {
      if (phase.tasks.empty()) continue;
      double sum = 0;
      size_t largest = 0;
      std::string times;
      nlohmann::ordered_json tasks = nlohmann::ordered_json::array();
      const cpu::fast::PhaseSchedule schedule = cpu::fast::schedule_phase(phase);
      for (size_t i = 0; i < phase.tasks.size(); ++i) {
        sum += phase.tasks[i].seconds;
        if (phase.tasks[i].seconds > phase.tasks[largest].seconds) largest = i;
        times += fmt::format(" {:.1f}", phase.tasks[i].seconds * 1e6);
        tasks.push_back({{"seconds", phase.tasks[i].seconds}, {"worker", schedule.workers[i]}});
      }
      const double projected = schedule.seconds;
      text += fmt::format(
          "{} at {} workers, {}: {} tasks, {:.1f} us of CPU, the largest {:.1f} us (task {}), "
          "the phase projected {:.1f} us; us in queue order:{}\n",
          scene, workers, phase.phase, phase.tasks.size(), sum * 1e6, phase.tasks[largest].seconds * 1e6, largest,
          projected * 1e6, times);
      out.push_back({{"scene", scene}, {"phase", phase.phase}, {"projected_seconds", projected}, {"tasks", tasks}});
    }
  }
  return out;
}

// --tasks: where each scene's serial time at N workers goes (its median profile): the calling
// thread's time before each phase and after the last; a line each appended to `text`, and as JSON.
nlohmann::ordered_json describe_serial(const ModelPoint& point, uint32_t workers, std::string& text) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const auto& [scene, profile] : point.profiles) {
    std::string parts;
    nlohmann::ordered_json before = nlohmann::ordered_json::array();
    for (const cpu::fast::PhaseTimes& phase : profile.phases) {
      parts += fmt::format(" {:.1f} before {},", phase.serial_before * 1e6, phase.phase);
      before.push_back({{"phase", phase.phase}, {"seconds", phase.serial_before}});
    }
    text += fmt::format("{} at {} workers, serial {:.1f} us:{} {:.1f} after the last phase\n", scene, workers,
                        profile.serial_seconds * 1e6, parts, profile.serial_after() * 1e6);
    out.push_back({{"scene", scene},
                   {"serial_seconds", profile.serial_seconds},
                   {"before_phases", before},
                   {"after_last_phase_seconds", profile.serial_after()}});
  }
  return out;
}

}  // namespace

int run_scaling_model(const BenchArgs& args) {
  std::vector<BenchCase> cases = make_cases(args);
  const std::vector<uint32_t>& counts = kModelWorkers;
  const uint32_t cores = host_usable_cpus();
  CpuOptions options;
  options.fma = lavapipe_fuses_on_this_host();
  bench::LoadMonitor load;
  load.start();
  fmt::print("CPU: {} ({} hardware threads, {} usable), fast path kernels: {}\n", cpu_model(),
             std::thread::hardware_concurrency(), cores, fast_kernels());
  fmt::print(
      "fast path on N workers, projected from each worker's thread CPU time per phase; {} reps, each rep every N "
      "in turn, each scene's profile the median of its reps'; each interval less the clock's own cost, {:.2f} us\n",
      args.reps, thread_cpu_clock_cost() * 1e6);
  fmt::print(
      "projected = serial + per phase its busiest worker (queue phases: their tasks list-scheduled on N); "
      "speed-up: projected(1) / projected(N); measured: wall time of the same renders unprofiled, where N <= {} "
      "usable hardware threads\n\n",
      cores);
  fmt::print("| scene | N | projected ms | speed-up | measured ms | bands busiest/mean | largest phase |\n");
  fmt::print("|---|---:|---:|---:|---:|---:|---|\n");
  nlohmann::ordered_json j;
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["usable_cpus"] = cores;
  j["fast_kernels"] = fast_kernels();
  j["reps"] = args.reps;
  j["clock_cost_seconds"] = thread_cpu_clock_cost();
  std::vector<experiments::DataBlock> blocks;
  std::string plot = "plot ";
  std::string tasks_text, serial_text;  // --tasks, after the table
  std::string fault_text;               // each case's page faults in its profiled renders
  for (BenchCase& c : cases) {
    std::vector<Scene> kept;  // the scenes the CPU profile supports
    std::vector<RenderResult> results;
    keep_supported(c.scenes, options, kept, results);
    experiments::DataBlock block{c.name, {{"workers", "speedup", experiments::gp_quote(c.name)}}};
    nlohmann::ordered_json row{{"name", c.name}};
    // every N in turn within a rep (ModelRep)
    ProfileStore store;
    ModelScratch scratch;
    std::vector<std::vector<ModelRep>> reps(counts.size(), std::vector<ModelRep>(args.reps, ModelRep(kept.size())));
    for (unsigned rep = 0; rep < args.reps; ++rep)
      for (size_t k = 0; k < counts.size(); ++k)
        model_rep(reps[k][rep], store, scratch, kept, results, options, counts[k], c.side_by_side, counts[k] <= cores);
    // the first rep's renders set up the pools' threads and the scratch: counted apart
    long first = 0, later = 0;
    for (const std::vector<ModelRep>& of_n : reps)
      for (size_t r = 0; r < of_n.size(); ++r) (r == 0 ? first : later) += of_n[r].faults;
    fault_text += fmt::format("{}: {} in the first rep's profiled renders, {} in the {} other reps'\n", c.name, first,
                              later, args.reps - 1);
    row["page_faults_profiled"] = {{"first_rep", first}, {"other_reps", later}};
    double one = 0;
    for (size_t k = 0; k < counts.size(); ++k) {
      const uint32_t n = counts[k];
      const ModelPoint point = model_point(reps[k], store, kept, n);
      if (n == 1) one = point.projected;
      const double speedup = point.projected > 0 ? one / point.projected : 0;
      const auto largest = std::max_element(point.phases.begin(), point.phases.end(),
                                            [](const auto& a, const auto& b) { return a.second < b.second; });
      fmt::print("| {} | {} | {:.2f} | {:.2f}x | {} | {:.2f} | {} {:.0f}% |\n", c.name, n, point.projected * 1e3,
                 speedup, n <= cores ? fmt::format("{:.2f}", point.wall * 1e3) : std::string("-"), point.worker_spread,
                 largest->first, point.projected > 0 ? 100.0 * largest->second / point.projected : 0.0);
      const nlohmann::ordered_json tasks =
          n == args.tasks_at ? describe_tasks(point, n, tasks_text) : nlohmann::ordered_json();
      const nlohmann::ordered_json serial =
          n == args.tasks_at ? describe_serial(point, n, serial_text) : nlohmann::ordered_json();
      std::fflush(stdout);
      block.rows.push_back({fmt::format("{}", n), fmt::format("{}", speedup), "x"});
      nlohmann::ordered_json phases;
      for (const auto& [name, seconds] : point.phases) phases[name] = seconds;
      row["workers"].push_back({{"workers", n},
                                {"projected_seconds", point.projected},
                                {"projected_speedup", speedup},
                                {"measured_wall_seconds", n <= cores ? nlohmann::json(point.wall) : nlohmann::json()},
                                {"bands_busiest_over_mean", point.worker_spread},
                                {"phases_busiest_seconds", phases}});
      if (n == args.tasks_at) {
        row["workers"].back()["tasks"] = tasks;
        row["workers"].back()["serial_parts"] = serial;
      }
    }
    plot += fmt::format("DATA index {} using 1:2 title columnheader(3) with linespoints lw 2 pt 7, ", blocks.size());
    blocks.push_back(std::move(block));
    j["scenes"].push_back(std::move(row));
  }
  load.stop();
  fmt::print("\npage faults in the profiled renders (first touches of pages, 10-35 us each on a shared VM):\n{}",
             fault_text);
  if (args.tasks_at != 0) {
    fmt::print("\nqueue phases' tasks at {} workers (thread CPU time; --tasks):\n{}", args.tasks_at,
               tasks_text.empty() ? std::string("none: no scene ran a queue phase\n") : tasks_text);
    fmt::print("\nthe calling thread's serial time at {} workers, us (--tasks):\n{}", args.tasks_at, serial_text);
  }
  j["load"] = {{"other_processes_cores", load.other_cores()},
               {"this_run_cores", load.own_cores()},
               {"load_average_1min", load.load_average_1min()},
               {"seconds", load.wall_seconds()}};
  fmt::print("\nload: other processes kept {:.2f} of the cores busy on average, this run {:.2f}, over {:.1f} s\n",
             load.other_cores(), load.own_cores(), load.wall_seconds());
  if (!args.json_path.empty()) {
    std::ofstream out(args.json_path);
    if (!out) throw UsageError("--json " + args.json_path + ": cannot write the file");
    out << j.dump(2) << "\n";
  }
  const std::string body =
      "set title " + experiments::gp_quote("fast path: projected speed-up on N cores (" + cpu_model() + ")") +
      " noenhanced\nset logscale xy 2\nset xlabel 'workers N'\nset ylabel 'projected speed-up over 1 worker'\n"
      "set key outside right top\nset grid\n" +
      plot + "x title 'ideal' with lines dt 2 lc rgb 'gray'\n";
  write_chart(args.chart_dir, "bench_scaling_model", blocks, body);
  return kExitOk;
}

}  // namespace rastercmp::app
