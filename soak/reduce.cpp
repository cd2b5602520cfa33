#include "soak/reduce.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "soak/primitives.hpp"

namespace rastercmp::soak {
namespace {

class Reducer {
 public:
  Reducer(Scene scene, const StillFails& still_fails, size_t max_runs)
      : best_(std::move(scene)), still_fails_(still_fails), max_runs_(max_runs) {}

  Scene run(ReduceStats& stats) {
    stats.primitives_before = primitive_count(best_);
    stats.draws_before = best_.draws.size();
    for (bool progress = true; progress && !out_of_runs();) {
      progress = false;
      progress |= drop_draws();
      progress |= unroll();
      progress |= drop_primitives();
      progress |= compact_positions();
      progress |= reset_state();
      progress |= simplify_coordinates();
    }
    stats.runs = runs_;
    stats.hit_limit = out_of_runs();
    stats.primitives_after = primitive_count(best_);
    stats.draws_after = best_.draws.size();
    return best_;
  }

 private:
  bool out_of_runs() const { return runs_ >= max_runs_; }

  // Keeps the candidate when it still fails.
  bool attempt(const Scene& candidate) {
    if (out_of_runs()) return false;
    ++runs_;
    if (!still_fails_(candidate)) return false;
    best_ = candidate;
    return true;
  }

  // Complement-only ddmin over `count` items: `make(keep)` builds the candidate from the kept
  // item numbers. Returns whether anything was removed.
  template <class Make>
  bool ddmin(size_t count, Make make) {
    std::vector<size_t> items(count);
    for (size_t i = 0; i < count; ++i) items[i] = i;
    bool any = false;
    size_t n = 2;
    while (items.size() >= 2 && !out_of_runs()) {
      const size_t chunk = (items.size() + n - 1) / n;
      bool removed = false;
      for (size_t start = 0; start < items.size(); start += chunk) {
        std::vector<size_t> keep(items.begin(), items.begin() + std::ptrdiff_t(start));
        keep.insert(keep.end(), items.begin() + std::ptrdiff_t(std::min(items.size(), start + chunk)), items.end());
        if (keep.empty()) continue;
        if (attempt(make(keep))) {
          items = keep;
          n = std::max<size_t>(n - 1, 2);
          removed = any = true;
          break;
        }
      }
      if (!removed) {
        if (n >= items.size()) break;
        n = std::min(items.size(), 2 * n);
      }
    }
    return any;
  }

  bool drop_draws() {
    const Scene base = best_;
    return ddmin(base.draws.size(), [&](const std::vector<size_t>& keep) {
      Scene s = base;
      s.draws.clear();
      for (size_t i : keep) s.draws.push_back(base.draws[i]);
      return s;
    });
  }

  static Topology list_of(Topology t) {
    if (t == Topology::TriangleStrip || t == Topology::TriangleFan) return Topology::TriangleList;
    if (t == Topology::LineStrip) return Topology::LineList;
    return t;
  }

  // Strips, fans and indexed draws → plain non-indexed lists of the same primitives.
  bool unroll() {
    bool any = false;
    for (size_t d = 0; d < best_.draws.size(); ++d) {
      const Draw& draw = best_.draws[d];
      if (draw.indices.empty() && list_of(draw.topology) == draw.topology) continue;
      Scene s = best_;
      Draw& out = s.draws[d];
      out.positions_clip.clear();
      out.indices.clear();
      out.topology = list_of(draw.topology);
      for (uint64_t p = 0; p < primitive_count(draw); ++p)
        for (uint32_t v : primitive_vertices(draw, p)) out.positions_clip.push_back(draw.positions_clip[v]);
      any |= attempt(s);
    }
    return any;
  }

  bool drop_primitives() {
    bool any = false;
    for (size_t d = 0; d < best_.draws.size() && !out_of_runs(); ++d) {
      const Scene base = best_;
      const Draw& draw = base.draws[d];
      if (list_of(draw.topology) != draw.topology) {  // strips and fans: trim a vertex off either end
        for (bool front : {false, true}) {
          if (front && draw.topology == Topology::TriangleFan) continue;  // a fan's first vertex is its centre
          while (primitive_count(best_.draws[d]) > 1 && !out_of_runs()) {
            Scene s = best_;
            Draw& out = s.draws[d];
            if (out.indices.empty()) {
              if (front)
                out.positions_clip.erase(out.positions_clip.begin());
              else
                out.positions_clip.pop_back();
            } else {
              if (front)
                out.indices.erase(out.indices.begin());
              else
                out.indices.pop_back();
            }
            if (!attempt(s)) break;
            any = true;
          }
        }
        continue;
      }
      const uint32_t k = vertices_per_primitive(draw.topology);
      any |= ddmin(size_t(primitive_count(draw)), [&](const std::vector<size_t>& keep) {
        Scene s = base;
        Draw& out = s.draws[d];
        if (draw.indices.empty()) {
          out.positions_clip.clear();
          for (size_t p : keep)
            for (uint32_t j = 0; j < k; ++j) out.positions_clip.push_back(draw.positions_clip[p * k + j]);
        } else {
          out.indices.clear();
          for (size_t p : keep)
            for (uint32_t j = 0; j < k; ++j) out.indices.push_back(draw.indices[p * k + j]);
        }
        return s;
      });
    }
    return any;
  }

  // Indexed draws: drop the positions no index uses, then try without indices at all.
  bool compact_positions() {
    bool any = false;
    for (size_t d = 0; d < best_.draws.size(); ++d) {
      const Draw& draw = best_.draws[d];
      if (draw.indices.empty()) continue;
      std::vector<uint32_t> remap(draw.positions_clip.size(), UINT32_MAX);
      Scene s = best_;
      Draw& out = s.draws[d];
      out.positions_clip.clear();
      for (uint32_t& i : out.indices) {
        if (remap[i] == UINT32_MAX) {
          remap[i] = uint32_t(out.positions_clip.size());
          out.positions_clip.push_back(draw.positions_clip[i]);
        }
        i = remap[i];
      }
      if (out.positions_clip.size() < draw.positions_clip.size()) any |= attempt(s);
    }
    return any;
  }

  bool try_change(const std::function<bool(Scene&)>& change) {
    Scene s = best_;
    if (!change(s)) return false;  // nothing to change
    return attempt(s);
  }

  bool reset_state() {
    bool any = false;
    any |= try_change([](Scene& s) { return s.scissor ? (s.scissor.reset(), true) : false; });
    any |= try_change([](Scene& s) {
      if (!s.viewport) return false;
      if (s.viewport->x == 0 && s.viewport->y == 0 && s.viewport->width == float(s.width) &&
          s.viewport->height == float(s.height))
        return false;
      // Keep the depth range, drop the rectangle.
      const Viewport old = *s.viewport;
      s.viewport = Viewport{0, 0, float(s.width), float(s.height), old.min_depth, old.max_depth};
      return true;
    });
    any |= try_change([](Scene& s) {
      if (!s.viewport || s.viewport->min_depth != 0 || s.viewport->max_depth != 1) {
        if (!s.viewport) return false;
        s.viewport->min_depth = 0;
        s.viewport->max_depth = 1;
        return true;
      }
      s.viewport.reset();
      return true;
    });
    any |= try_change([](Scene& s) { return s.samples != 1 ? (s.samples = 1, true) : false; });
    any |= try_change([](Scene& s) {
      return s.depth_format != DepthFormat::D32Sfloat ? (s.depth_format = DepthFormat::D32Sfloat, true) : false;
    });
    any |= try_change([](Scene& s) { return s.depth_clear != 1.0f ? (s.depth_clear = 1.0f, true) : false; });
    for (size_t d = 0; d < best_.draws.size(); ++d) {
      using Field = std::function<bool(RasterState&)>;
      const std::vector<Field> fields{
          [](RasterState& r) { return r.cull_mode != CullMode::None ? (r.cull_mode = CullMode::None, true) : false; },
          [](RasterState& r) {
            return r.front_face != FrontFace::CounterClockwise ? (r.front_face = FrontFace::CounterClockwise, true)
                                                               : false;
          },
          [](RasterState& r) {
            return r.polygon_mode != PolygonMode::Fill ? (r.polygon_mode = PolygonMode::Fill, true) : false;
          },
          [](RasterState& r) {
            return r.line_mode != LineMode::Default ? (r.line_mode = LineMode::Default, true) : false;
          },
          [](RasterState& r) { return r.line_width != 1 ? (r.line_width = 1, true) : false; },
          [](RasterState& r) { return !r.depth.test_enable ? (r.depth.test_enable = true, true) : false; },
          [](RasterState& r) { return !r.depth.write_enable ? (r.depth.write_enable = true, true) : false; },
          [](RasterState& r) {
            return r.depth.compare_op != CompareOp::Less ? (r.depth.compare_op = CompareOp::Less, true) : false;
          },
          [](RasterState& r) { return r.depth_bias.enable ? (r.depth_bias = DepthBias{}, true) : false; },
          [](RasterState& r) { return r.depth_clamp ? (r.depth_clamp = false, true) : false; },
          [](RasterState& r) { return r.depth_clip ? (r.depth_clip.reset(), true) : false; },
      };
      for (const Field& f : fields) any |= try_change([&](Scene& s) { return f(s.draws[d].state); });
    }
    return any;
  }

  // One vertex moved toward simpler numbers: step 0 divides by w (w = 1), steps 1..4 put the
  // pixel position on whole, half, 1/16 and 1/256 pixels and the depth on the same grid.
  static bool simplify_vertex(const Scene& s, glm::vec4& v, int step) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || !std::isfinite(v.w) || v.w == 0)
      return false;
    const glm::vec4 old = v;
    if (step == 0) {
      if (v.w <= 0 || v.w == 1) return false;
      v = glm::vec4(float(double(v.x) / v.w), float(double(v.y) / v.w), float(double(v.z) / v.w), 1.0f);
      return v != old;
    }
    const double denom = step == 1 ? 1 : step == 2 ? 2 : step == 3 ? 16 : 256;
    const Viewport vp = s.effective_viewport();
    const double ox = vp.x + vp.width / 2.0, oy = vp.y + vp.height / 2.0, w = v.w;
    const double pxx = ox + double(v.x) / w * vp.width / 2.0, pxy = oy + double(v.y) / w * vp.height / 2.0;
    const double sx = std::round(pxx * denom) / denom, sy = std::round(pxy * denom) / denom;
    const double z = std::round(double(v.z) / w * denom) / denom;
    v = glm::vec4(float(w * (sx - ox) / (vp.width / 2.0)), float(w * (sy - oy) / (vp.height / 2.0)), float(w * z),
                  float(w));
    return v != old;
  }

  bool simplify_coordinates() {
    bool any = false;
    for (int step = 0; step <= 4; ++step) {
      // The whole scene at once, then each draw, then each vertex.
      const bool all = try_change([&](Scene& s) {
        bool changed = false;
        for (Draw& d : s.draws)
          for (glm::vec4& v : d.positions_clip) changed |= simplify_vertex(s, v, step);
        return changed;
      });
      any |= all;
      if (all) continue;
      for (size_t d = 0; d < best_.draws.size(); ++d) {
        const bool whole = try_change([&](Scene& s) {
          bool changed = false;
          for (glm::vec4& v : s.draws[d].positions_clip) changed |= simplify_vertex(s, v, step);
          return changed;
        });
        any |= whole;
        if (whole || best_.draws[d].positions_clip.size() == 1) continue;
        for (size_t i = 0; i < best_.draws[d].positions_clip.size(); ++i)
          any |= try_change([&](Scene& s) { return simplify_vertex(s, s.draws[d].positions_clip[i], step); });
      }
    }
    return any;
  }

  Scene best_;
  const StillFails& still_fails_;
  size_t max_runs_;
  size_t runs_ = 0;
};

}  // namespace

Scene reduce_scene(const Scene& scene, const StillFails& still_fails, size_t max_runs, ReduceStats* stats) {
  ReduceStats local;
  Reducer reducer(scene, still_fails, max_runs);
  Scene result = reducer.run(stats ? *stats : local);
  return result;
}

}  // namespace rastercmp::soak
