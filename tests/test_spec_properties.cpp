// The key soundness check of the spec profile: lavapipe's rasterization, as the CPU lavapipe
// profile reproduces it bit for bit, is one conformant rasterization, so it must never cover a
// MustNot sample nor miss a Must sample, nor store a depth outside a sample's spec interval. Random triangles (on and
// off the sub-pixel grid, through pixel centres, clipped in x, y and z, behind the eye, culled), random lines, random
// depth state and random scenes of several draws with shared edges. CPU only.
//
// Known lavapipe deviation kept out of the generators: with 4x multisampling an inner scissor
// leaks half a pixel at its left and top edges (docs/lavapipe-rules.md §2.5); tests/test_spec_lavapipe.cpp
// shows that the profile catches it.
#include <algorithm>
#include <array>
#include <vector>

#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include "cpu_raster/spec/exact_owners.hpp"
#include "cpu_raster/spec/line_coverage.hpp"
#include "cpu_raster/spec/spec_primitives.hpp"
#include "cpu_raster/spec/spec_profile.hpp"
#include "cpu_raster/spec/triangle_coverage.hpp"
#include "model/camera.hpp"
#include "test_spec_support.hpp"

namespace rastercmp {
namespace {

using namespace spec_test;

// Uniform over [lo, hi] whatever rapidcheck's current size (inRange scales its range by size).
int pick(int lo, int hi) { return *rc::gen::resize(rc::kNominalSize, rc::gen::inRange(lo, hi + 1)); }
bool coin(int percent) { return pick(0, 99) < percent; }

// A window coordinate over [-margin, extent + margin]: on the 1/256 grid, on a pixel centre or
// corner, or anywhere.
double window_coordinate(double extent, double margin) {
  switch (pick(0, 2)) {
    case 0: return pick(int(-margin * 256), int((extent + margin) * 256)) / 256.0;
    case 1: return pick(int(-2 * margin), int(2 * (extent + margin))) / 2.0;
    default: return -margin + (extent + 2 * margin) * (pick(0, 1 << 20) / double(1 << 20));
  }
}

Viewport random_viewport(uint32_t w, uint32_t h) {
  if (coin(60)) return Viewport{0, 0, float(w), float(h), 0, 1};
  Viewport v;
  v.x = float(pick(-16, int(w) / 2) + (coin(50) ? pick(0, 3) / 4.0 : 0.0));
  v.y = float(pick(-16, int(h) / 2) + (coin(50) ? pick(0, 3) / 4.0 : 0.0));
  v.width = float(pick(4, int(w) + 8));
  v.height = float(pick(4, int(h) + 8)) * (coin(30) ? -1.0f : 1.0f);
  v.min_depth = float(pick(0, 4) / 8.0);
  v.max_depth = float(pick(5, 8) / 8.0);
  if (coin(20)) std::swap(v.min_depth, v.max_depth);
  return v;
}

// A vertex given in window pixels (relative to the framebuffer), a depth and a clip w, turned into
// clip space through the viewport; some vertices lie behind the eye.
glm::vec4 random_vertex(const Scene& scene) {
  const double x = window_coordinate(scene.width, coin(20) ? 24 : 2);
  const double y = window_coordinate(scene.height, coin(20) ? 24 : 2);
  const Viewport v = scene.effective_viewport();
  const double z_window =
      coin(15) ? pick(-40, 140) / 100.0 : v.min_depth + (v.max_depth - v.min_depth) * pick(0, 100) / 100.0;
  const float w = coin(10) ? -float(pick(1, 8)) / 4 : (coin(70) ? 1.0f : float(pick(1, 16)) / 4);
  return pixels_to_clip(v, glm::vec4(float(x), float(y), float(z_window), w));
}

RasterState random_state(bool lines) {
  RasterState s;
  s.cull_mode = coin(50) ? CullMode::None : CullMode(pick(1, 3));
  s.front_face = FrontFace(pick(0, 1));
  s.depth.test_enable = coin(80);
  s.depth.write_enable = coin(80);
  s.depth.compare_op = coin(70) ? CompareOp::Less : CompareOp(pick(0, 7));
  if (coin(25))
    s.depth_bias =
        DepthBias{true, float(pick(-40, 40)), float(pick(-8, 8)) / 4, coin(50) ? 0.0f : float(pick(-4, 4)) / 64};
  s.depth_clamp = coin(20);
  if (coin(15)) s.depth_clip = coin(50);
  if (lines) {
    s.line_mode = LineMode(pick(0, 2));
    s.line_width = coin(50) ? 1.0f : float(pick(4, 24)) / 4;
  }
  return s;
}

Scene random_frame() {
  Scene scene = make_scene(uint32_t(pick(4, 40)), uint32_t(pick(4, 40)), coin(30) ? 4 : 1);
  scene.depth_format = DepthFormat(pick(0, 3));
  scene.depth_clear = coin(75) ? 1.0f : float(pick(0, 8)) / 8;
  scene.viewport = random_viewport(scene.width, scene.height);
  if (scene.samples == 1 && coin(25))
    scene.scissor = Rect2D{pick(0, int(scene.width)), pick(0, int(scene.height)), uint32_t(pick(0, int(scene.width))),
                           uint32_t(pick(0, int(scene.height)))};
  return scene;
}

Draw random_draw(const Scene& scene, Topology topology, int primitives) {
  Draw draw;
  draw.topology = topology;
  draw.state = random_state(is_line_topology(topology));
  const int vertices = topology == Topology::TriangleList ? 3 * primitives
                       : topology == Topology::LineList   ? 2 * primitives
                       : topology == Topology::LineStrip  ? primitives + 1
                                                          : primitives + 2;
  for (int k = 0; k < vertices; ++k) draw.positions_clip.push_back(random_vertex(scene));
  // A known lavapipe deviation, kept out of this property (docs/spec-profile.md "Lavapipe
  // deviations"): at 4x a Bresenham fragment is depth-tested at sample 0 only and its owner written
  // to all four samples (docs/lavapipe-rules.md §6), which breaks the per-sample depth test.
  if (scene.samples > 1 && draw.state.line_mode == LineMode::Bresenham) draw.state.depth.test_enable = false;
  if (coin(30) && topology == Topology::TriangleList) {  // reuse vertices: shared edges
    draw.indices.clear();
    for (int k = 0; k < vertices; ++k) draw.indices.push_back(uint32_t(pick(0, std::min(vertices - 1, 4))));
  }
  return draw;
}

// Scenes per property case: rapidcheck runs 100 cases by default (RC_PARAMS="max_success=N" for
// more), each checks this many scenes.
constexpr int kScenesPerCase = 8;

// docs/spec-profile.md "Lavapipe deviations": in a 4x framebuffer a Bresenham line writes its owner
// to all four samples but its depth to sample 0 only.
bool has_multisample_bresenham_line(const Scene& scene) {
  return scene.samples > 1 && std::any_of(scene.draws.begin(), scene.draws.end(), [](const Draw& d) {
           return is_line_topology(d.topology) && d.state.line_mode == LineMode::Bresenham;
         });
}

// From Mesa 23.2 lavapipe does not clip lines in x and y (docs/lavapipe-rules.md §8.2): a line
// with an endpoint at w <= 0 that no depth plane clips (depth clipping off) is drawn between the
// projected endpoints, one of them projected through the eye, so its fragments lie off the segment.
// A deviation, documented in docs/spec-profile.md "Lavapipe deviations": such scenes are judged
// with the releases before it only.
bool draws_external_line(const Scene& scene, const LavapipeRelease& release) {
  if (!release.rules().has(LavapipeRule::LineGuardBand)) return false;
  return std::any_of(scene.draws.begin(), scene.draws.end(), [](const Draw& d) {
    return is_line_topology(d.topology) && std::any_of(d.positions_clip.begin(), d.positions_clip.end(),
                                                       [](const glm::vec4& p) { return !(p.w > 0.0f); });
  });
}

// Coverage by class, and every stored depth inside its spec interval (but for the deviation above,
// and depth extrapolated past a triangle's vertices, accept_float_plane_extrapolation).
void check_lavapipe_is_accepted(const Scene& scene, uint32_t bits,
                                const LavapipeRelease& release = lavapipe_releases().front()) {
  RC_CLASSIFY(draws_external_line(scene, release), "external line: judged with 22.3's rules");
  const RenderResult exact =
      render_cpu(scene, lavapipe_options(draws_external_line(scene, release) ? lavapipe_releases().front() : release));
  RenderResult spec = render_spec_profile(scene, spec_options(bits), exact);
  RC_CLASSIFY(accept_float_plane_extrapolation(scene, bits, spec, exact) > 0, "lavapipe extrapolates depth");
  const Violations v = has_multisample_bresenham_line(scene) ? judge(spec.coverage_class, exact) : judge(spec, exact);
  RC_CLASSIFY(v.must > 0, "some Must");
  RC_CLASSIFY(v.may > 0, "some May");
  RC_CLASSIFY(std::any_of(exact.owner.begin(), exact.owner.end(), [](uint32_t o) { return o != kOwnerBackground; }),
              "lavapipe covers something");
  if (v.any()) RC_LOG() << describe(v) << "\n" << describe(scene);
  RC_ASSERT_FALSE(v.any());
}

RC_GTEST_PROP(SpecProfileProperty, LavapipeNeverViolatesOneTriangle, ()) {
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    scene.draws.push_back(random_draw(scene, Topology::TriangleList, 1));
    check_lavapipe_is_accepted(scene, 8);
  }
}

// A device with fewer sub-pixel bits than lavapipe's 8 has coarser cells, which contain lavapipe's
// snapped positions: lavapipe stays accepted.
RC_GTEST_PROP(SpecProfileProperty, LavapipeNeverViolatesOnACoarserGrid, ()) {
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    scene.draws.push_back(random_draw(scene, Topology::TriangleStrip, pick(1, 4)));
    check_lavapipe_is_accepted(scene, uint32_t(pick(4, 8)));
  }
}

// Every modelled lavapipe release: from Mesa 23.2 lines are not clipped in x and y (a guard band,
// docs/lavapipe-rules.md §8.2), which the spec allows ("the line segment may be clipped").
const LavapipeRelease& random_release() {
  const LavapipeRelease& release = lavapipe_releases()[size_t(pick(0, int(lavapipe_releases().size()) - 1))];
  RC_CLASSIFY(true, release.profile);
  return release;
}

RC_GTEST_PROP(SpecProfileProperty, LavapipeNeverViolatesLines, ()) {
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    scene.draws.push_back(random_draw(scene, coin(50) ? Topology::LineList : Topology::LineStrip, pick(1, 3)));
    check_lavapipe_is_accepted(scene, 8, random_release());
  }
}

RC_GTEST_PROP(SpecProfileProperty, LavapipeNeverViolatesScenes, ()) {
  const std::vector<Topology> topologies = {Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan,
                                            Topology::LineList, Topology::LineStrip};
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    const int draws = pick(1, 4);
    for (int d = 0; d < draws; ++d)
      scene.draws.push_back(random_draw(scene, topologies[size_t(pick(0, 4))], pick(1, 6)));
    check_lavapipe_is_accepted(scene, 8, random_release());
  }
}

// The devices exact_owners.hpp simulates are conformant rasterizations too, computed independently
// of the classification (exact edge functions on their own snapped vertices, a tie rule, the depth
// test in draw order): each must cover every Must sample and no MustNot sample, and where it leaves
// another owner than the estimate at a Must sample, that owner is among the sample's alternatives.
RC_GTEST_PROP(SpecProfileProperty, ExactDevicesNeverViolateAndTheirOwnersAreListed, ()) {
  const std::vector<Topology> topologies = {Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan};
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    const int draws = pick(1, 4);
    for (int d = 0; d < draws; ++d)
      scene.draws.push_back(random_draw(scene, topologies[size_t(pick(0, 2))], pick(1, 4)));
    const uint32_t bits = coin(80) ? 8 : uint32_t(pick(4, 8));
    const RenderResult spec = render_spec_profile(scene, spec_options(bits), render_cpu(scene, lavapipe_options()));
    const cpu::spec::SpecPrimitives primitives = cpu::spec::build_spec_primitives(scene, true, bits);
    if (primitives.undefined) continue;
    RC_CLASSIFY(!spec.owner_alternatives.empty(), "some alternatives");
    for (const cpu::spec::ExactDevice& device : cpu::spec::exact_devices(scene)) {
      const std::vector<uint32_t> owners = cpu::spec::exact_device_owners(scene, primitives.triangles, bits, device);
      for (size_t i = 0; i < owners.size(); ++i) {
        const CoverageClass c = spec.coverage_class[i];
        const bool covered = owners[i] != kOwnerBackground;
        if ((c == CoverageClass::Must && !covered) || (c == CoverageClass::MustNot && covered)) {
          RC_LOG() << "sample " << i << " class " << int(c) << " owner " << owners[i] << " device snap "
                   << int(device.snap) << " tie " << int(device.tie) << "\n"
                   << describe(scene);
          RC_FAIL("an exact device breaks the classes");
        }
        // (Small scenes of triangles only: never over kExactOwnerWorkLimit.)
        if (c == CoverageClass::Must && owners[i] != spec.owner[i]) RC_ASSERT(is_owner_alternative(spec, i, owners[i]));
      }
    }
  }
}

// docs/spec-profile.md "Owners", open owners: where a line may cover a sample but certainly does
// not, a device may leave the line out there. Lavapipe's render of the same scene without its lines
// is what such a device leaves where no line certainly covers: at every Must sample there its owner
// must be the estimate's or an alternative. (With the triangles' depths inside their intervals, as
// the properties above check, no certain triangle certainly beats that owner.)
RC_GTEST_PROP(SpecProfileProperty, LinesLeftOutLeaveAnAllowedOwner, ()) {
  using namespace cpu::spec;
  const std::vector<Topology> triangles = {Topology::TriangleList, Topology::TriangleStrip, Topology::TriangleFan};
  uint64_t checked = 0;
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    Scene without = scene;
    const int draws = pick(2, 5);
    for (int d = 0; d < draws; ++d) {
      const bool line = d == 0 || coin(40);
      const Draw draw = random_draw(
          scene, line ? (coin(50) ? Topology::LineList : Topology::LineStrip) : triangles[size_t(pick(0, 2))],
          pick(1, 4));
      scene.draws.push_back(draw);
      if (!line) without.draws.push_back(draw);
    }
    if (has_multisample_bresenham_line(scene)) continue;  // a lavapipe deviation (above)
    const RenderResult estimate = render_cpu(scene, lavapipe_options());
    RenderResult spec = render_spec_profile(scene, spec_options(8), estimate);
    const RenderResult left_out = render_cpu(without, lavapipe_options());
    // The owner ids of `without` count its draws without the lines: map them back.
    std::vector<uint32_t> draw_of;
    for (uint32_t d = 0; d < scene.draws.size(); ++d)
      if (!is_line_topology(scene.draws[d].topology)) draw_of.push_back(d);
    const SpecPrimitives primitives = build_spec_primitives(scene, true, 8);
    if (primitives.undefined) continue;
    // Lavapipe's depth extrapolated past a triangle's vertices is a deviation (above) that can
    // also turn the depth test: such scenes are left out.
    RenderResult spec_without = render_spec_profile(without, spec_options(8), left_out);
    if (accept_float_plane_extrapolation(without, 8, spec_without, left_out) > 0) continue;
    const bool multisample = scene.samples > 1;
    for (uint32_t y = 0; y < scene.height; ++y)
      for (uint32_t x = 0; x < scene.width; ++x) {
        const bool line_certain = std::any_of(primitives.lines.begin(), primitives.lines.end(), [&](const SpecLine& l) {
          return line_coverage_at(l, int32_t(x), int32_t(y), 8, multisample) == Coverage::Full &&
                 depth_gate_at(l.depth, glm::dvec2(x + 0.5, y + 0.5)) == Gate::Certain;
        });
        if (line_certain) continue;
        for (uint32_t s = 0; s < scene.samples; ++s) {
          const size_t i = spec.index(x, y, s);
          if (spec.coverage_class[i] != CoverageClass::Must || left_out.owner[i] == kOwnerBackground) continue;
          const uint32_t owner =
              encode_owner(draw_of[owner_draw(left_out.owner[i])], owner_primitive(left_out.owner[i]));
          ++checked;
          if (owner != spec.owner[i] && !is_owner_alternative(spec, i, owner)) {
            RC_LOG() << "sample (" << x << ", " << y << ") " << s << ": without the lines " << owner << ", estimate "
                     << spec.owner[i] << "\n"
                     << describe(scene);
            RC_FAIL("a device that leaves the lines out leaves an owner the profile does not allow");
          }
        }
      }
  }
  RC_CLASSIFY(checked > 0, "some Must sample checked");
}

// "The floating-point viewport bounds are represented with an implementation-dependent precision"
// (viewportSubPixelBits, at least 0): lavapipe's render with the viewport's x, y, width and height
// each rounded down or up to whole pixels is one conformant render of a scene whose bounds are
// fractional, judged with viewportSubPixelBits 0.
RC_GTEST_PROP(SpecProfileProperty, EveryRepresentedViewportIsAccepted, ()) {
  for (int k = 0; k < kScenesPerCase; ++k) {
    Scene scene = random_frame();
    Viewport v = scene.effective_viewport();
    v.x += float(pick(0, 255)) / 256;
    v.y += float(pick(0, 255)) / 256;
    v.width += float(pick(0, 255)) / 256;
    v.height += float(pick(0, 255)) / 256 * (v.height < 0 ? -1 : 1);
    scene.viewport = v;
    const int draws = pick(1, 3);
    for (int d = 0; d < draws; ++d)
      scene.draws.push_back(random_draw(scene, coin(25) ? Topology::LineList : Topology::TriangleList, pick(1, 4)));
    if (has_multisample_bresenham_line(scene)) continue;
    CpuOptions options = spec_options(8);
    options.viewport_sub_pixel_bits = 0;
    const RenderResult spec = render_spec_profile(scene, options, render_cpu(scene, lavapipe_options()));
    Scene held = scene;
    const auto rounded = [](float value) { return coin(50) ? std::floor(value) : std::ceil(value); };
    held.viewport = Viewport{rounded(v.x), rounded(v.y), rounded(v.width), rounded(v.height), v.min_depth, v.max_depth};
    if (held.viewport->width == 0 || held.viewport->height == 0) continue;
    const RenderResult exact = render_cpu(held, lavapipe_options());
    RenderResult widened = spec;
    RenderResult spec_held = render_spec_profile(held, spec_options(8), exact);
    if (accept_float_plane_extrapolation(held, 8, spec_held, exact) > 0) continue;  // a deviation (above)
    const Violations violations = judge(widened, exact);
    if (violations.any()) RC_LOG() << describe(violations) << "\n" << describe(held);
    RC_ASSERT_FALSE(violations.any());
  }
}

// A grid of quads split into triangle pairs (a strip per row): every inner edge is shared, so
// promotion decides most centres on them; lavapipe's top-left rule covers each exactly once.
RC_GTEST_PROP(SpecProfileProperty, LavapipeNeverViolatesSharedEdgeGrids, ()) {
  Scene scene = random_frame();
  const int columns = pick(1, 5), rows = pick(1, 4);
  std::vector<std::vector<glm::vec4>> grid(size_t(rows + 1));
  for (int r = 0; r <= rows; ++r)
    for (int c = 0; c <= columns; ++c) grid[size_t(r)].push_back(random_vertex(scene));
  Draw draw;
  draw.state = random_state(false);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const glm::vec4 a = grid[size_t(r)][size_t(c)], b = grid[size_t(r)][size_t(c + 1)];
      const glm::vec4 d = grid[size_t(r + 1)][size_t(c)], e = grid[size_t(r + 1)][size_t(c + 1)];
      draw.positions_clip.insert(draw.positions_clip.end(), {a, b, d, b, e, d});
    }
  scene.draws.push_back(draw);
  check_lavapipe_is_accepted(scene, 8);
}

// The per-row spans the renderer uses are exactly classify_box's answers, pixel by pixel.
RC_GTEST_PROP(SpecProfileProperty, RowSpansAgreeWithThePerPixelClassification, ()) {
  using namespace cpu::spec;
  const uint32_t bits = uint32_t(pick(1, 16));
  const bool multisample = coin(30);
  std::array<glm::dvec2, 3> v;
  for (glm::dvec2& p : v) p = {window_coordinate(24, 4), window_coordinate(24, 4)};
  const SnappedTriangle t = snap_triangle(v, bits);
  for (int32_t py = -6; py <= 30; ++py) {
    const RowSpans spans = row_spans(t, py, bits, multisample);
    for (int32_t px = -6; px <= 30; ++px) {
      const Coverage expected = classify_box(t, pixel_box(px, py, bits, multisample));
      const bool touched = px >= spans.touch_first && px <= spans.touch_last;
      const bool full = px >= spans.full_first && px <= spans.full_last;
      RC_ASSERT(touched == (expected != Coverage::None));
      RC_ASSERT(full == (expected == Coverage::Full));
    }
  }
}

// The rows and columns the renderer visits for a line hold every box classify_line_box does not
// call NONE.
RC_GTEST_PROP(SpecProfileProperty, LineBandsHoldEveryTouchedBox, ()) {
  using namespace cpu::spec;
  const std::array<glm::dvec2, 2> ends = {glm::dvec2(window_coordinate(24, 4), window_coordinate(24, 4)),
                                          glm::dvec2(window_coordinate(24, 4), window_coordinate(24, 4))};
  const LineShape shape = line_shape(ends, LineMode(pick(0, 2)), float(pick(4, 40)) / 4);
  const double half_px = coin(30) ? 0.5 + 3.0 / 256 : 3.0 / 256;
  const double reach = half_px + kLineMarginPx;
  const PixelBounds b = may_bounds(shape);
  for (int32_t py = -16; py <= 40; ++py) {
    const XExtent e = may_extent_in_band(shape, py + 0.5 - reach, py + 0.5 + reach);
    for (int32_t px = -16; px <= 40; ++px) {
      if (classify_line_box(shape, PixelSquare{glm::dvec2(px + 0.5, py + 0.5), half_px}) == Coverage::None) continue;
      RC_ASSERT(py >= std::ceil(b.y_min - half_px - 0.5) && py <= std::floor(b.y_max + half_px - 0.5));
      RC_ASSERT(px >= std::ceil(e.x_min - reach - 0.5) && px <= std::floor(e.x_max + reach - 0.5));
    }
  }
}

}  // namespace
}  // namespace rastercmp
