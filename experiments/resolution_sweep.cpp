#include "experiments/resolution_sweep.hpp"

#include <cmath>
#include <stdexcept>

#include "experiments/progress.hpp"
#include "experiments/speed_accuracy.hpp"
#include "model/errors.hpp"

namespace rastercmp::experiments {

std::vector<ResolutionMethod> resolution_methods() {
  std::vector<ResolutionMethod> out;
  for (const MethodEntry& e : speed_accuracy_entries()) {
    if (e.cpu.threads != 0 || e.family == "exact path" || e.family == "depth format") continue;
    const bool edge = e.family == "fill" || e.family == "set-up" || e.family == "line" || e.family == "line clipping";
    out.push_back({e.family, e.method, e.cpu, e.lines, edge ? 1 : 2});
  }
  return out;
}

std::vector<Scene> resolution_scenes(bool lines, uint32_t size) {
  std::vector<Scene> scenes = speed_accuracy_scenes(lines);
  for (Scene& scene : scenes) {
    const double scale = double(size) / double(scene.width);
    if (scene.width != scene.height) throw std::logic_error("resolution_scenes: a scene of the set is not square");
    if (scene.viewport) {  // the same fraction of the frame
      scene.viewport->x = float(scene.viewport->x * scale);
      scene.viewport->y = float(scene.viewport->y * scale);
      scene.viewport->width = float(scene.viewport->width * scale);
      scene.viewport->height = float(scene.viewport->height * scale);
    }
    if (scene.scissor) throw std::logic_error("resolution_scenes: a scene of the set has a scissor");
    scene.width = scene.height = size;
  }
  return scenes;
}

std::vector<uint32_t> resolution_sizes(bool quick) {
  if (quick) return {64, 128, 256, 512};
  return {64, 128, 256, 512, 1024, 2048, 4096};
}

std::vector<ResolutionPoint> measure_resolution(const std::vector<ResolutionMethod>& methods,
                                                const std::vector<uint32_t>& sizes) {
  std::vector<ResolutionPoint> points;
  for (const ResolutionMethod& m : methods)
    for (uint32_t size : sizes) points.push_back({m.family, m.method, size});
  Progress progress("chart resolution", sizes.size() * 2);
  const CpuOptions exact = exact_cpu_options();
  // One size and one scene at a time, the exact render kept while every method of its set renders:
  // at 4096 a render holds 128 MiB.
  for (uint32_t size_index = 0; size_index < sizes.size(); ++size_index)
    for (bool lines : {false, true}) {
      for (const Scene& scene : resolution_scenes(lines, sizes[size_index])) {
        const RenderResult reference = render_cpu(scene, exact);
        for (size_t k = 0; k < methods.size(); ++k) {
          if (methods[k].lines != lines) continue;
          ResolutionPoint& p = points[k * sizes.size() + size_index];
          if (p.refused) continue;
          RenderResult result;
          try {
            result = render_cpu(scene, methods[k].cpu);
          } catch (const NotSupportedError&) {
            p.refused = true;
            continue;
          }
          for (size_t i = 0; i < reference.owner.size(); ++i) {
            const bool owner = reference.owner[i] != result.owner[i];
            const bool depth = reference.has_depth() && reference.depth_raw[i] != result.depth_raw[i];
            p.coverage += owner ? 1 : 0;
            p.depth += depth ? 1 : 0;
            p.either += owner || depth ? 1 : 0;
          }
          p.samples += reference.owner.size();
        }
      }
      progress.finished();
    }
  progress.done();
  return points;
}

double count_exponent(const std::vector<ResolutionPoint>& points) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const ResolutionPoint& p : points) {
    if (p.refused || p.either == 0) continue;
    const double x = std::log2(double(p.size)), y = std::log2(double(p.either));
    n += 1;
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  if (n < 2) return NAN;
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace rastercmp::experiments
