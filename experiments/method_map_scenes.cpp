#include "experiments/method_map_scenes.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "model/camera.hpp"

namespace rastercmp::experiments {
namespace {

constexpr double kSubpixel = 1.0 / 256.0;

Scene window_scene(const char* name) {
  Scene scene;
  scene.name = std::string("experiments.") + name;
  scene.depth_format = DepthFormat::D32Sfloat;
  return scene;
}

Draw pixel_triangles(const Scene& scene, const std::vector<glm::dvec3>& pixels) {
  Draw draw;
  const Viewport viewport = scene.effective_viewport();
  for (const glm::dvec3& p : pixels)
    draw.positions_clip.push_back(pixels_to_clip(viewport, glm::vec4(float(p.x), float(p.y), float(p.z), 1)));
  return draw;
}

// Two triangles of a quad a b c d.
void push_quad(std::vector<glm::dvec3>& out, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
  out.insert(out.end(), {a, b, c, a, c, d});
}

// The scene's vertices are floats: the design keeps them as the scene stores them.
WindowTriangle on_floats(const WindowTriangle& t) {
  WindowTriangle out;
  for (size_t i = 0; i < 3; ++i) out[i] = {double(float(t[i].x)), double(float(t[i].y))};
  return out;
}

// One draw of the design's triangles at window depth 0.5.
Draw design_draw(const Scene& scene, const DesignTriangles& design) {
  std::vector<glm::dvec3> pixels;
  for (const WindowTriangle& t : design.triangles)
    for (const glm::dvec2& v : t) pixels.push_back({v.x, v.y, 0.5});
  return pixel_triangles(scene, pixels);
}

// Bar i of make_cyclic_bars: direction at 90 + 120 i degrees, its centre line 8 pixels from the frame
// centre, half-length 28, half-width 3; window depth mean + tilt * s along it (s in -1..1).
constexpr double kBarOffset = 8, kBarHalfLength = 28, kBarHalfWidth = 3;

}  // namespace

DesignTriangles sliver_strip_design(double width_subpx) {
  const double w = width_subpx * kSubpixel;
  return {{on_floats({glm::dvec2(4.0, 10.5 - 0.3 * w), glm::dvec2(60.0, 10.5 + 0.2 * w), glm::dvec2(4.0, 10.5 + 0.7 * w)})},
          64,
          64};
}

Scene make_sliver_strip(double width_subpx) {
  Scene scene = window_scene("sliver_strip");
  scene.draws.push_back(design_draw(scene, sliver_strip_design(width_subpx)));
  return scene;
}

DesignTriangles fan_design(double offset_subpx) {
  const glm::dvec2 centre(16.5 + offset_subpx * kSubpixel, 16.5 + offset_subpx * kSubpixel);
  DesignTriangles design{{}, 64, 64};
  for (int k = 0; k < 8; ++k) {
    const double a0 = k * std::numbers::pi / 4, a1 = (k + 1) * std::numbers::pi / 4;
    design.triangles.push_back(on_floats({centre, glm::dvec2(16.5 + 12 * std::cos(a0), 16.5 + 12 * std::sin(a0)),
                                          glm::dvec2(16.5 + 12 * std::cos(a1), 16.5 + 12 * std::sin(a1))}));
  }
  return design;
}

Scene make_fan(double offset_subpx) {
  Scene scene = window_scene("fan");
  scene.draws.push_back(design_draw(scene, fan_design(offset_subpx)));
  return scene;
}

double cyclic_bars_onset_tilt() {
  // Bar i meets bar i+1 at s = +a and bar i-1 at s = -a, a = offset * tan(60 deg) / half-length.
  return 0.05 / (kBarOffset * std::sqrt(3.0) / kBarHalfLength);
}

Scene make_cyclic_bars(double tilt) {
  Scene scene = window_scene("cyclic_bars");
  const glm::dvec2 centre(32, 32);
  for (int i = 0; i < 3; ++i) {
    const double angle = (90.0 + 120.0 * i) * std::numbers::pi / 180.0;
    const glm::dvec2 d(std::cos(angle), std::sin(angle)), n(d.y, -d.x);
    const glm::dvec2 mid = centre + n * kBarOffset;
    const double mean = 0.4 + 0.1 * i;
    const auto at = [&](double s, double across) {
      const glm::dvec2 p = mid + d * (s * kBarHalfLength) + n * across;
      return glm::dvec3(p.x, p.y, mean + tilt * s);
    };
    std::vector<glm::dvec3> pixels;
    push_quad(pixels, at(-1, -kBarHalfWidth), at(1, -kBarHalfWidth), at(1, kBarHalfWidth), at(-1, kBarHalfWidth));
    scene.draws.push_back(pixel_triangles(scene, pixels));
  }
  return scene;
}

Scene make_interpenetration(double penetration) {
  Scene scene = window_scene("interpenetration");
  std::vector<glm::dvec3> front, tilted;
  push_quad(front, {8, 8, 0.5}, {56, 8, 0.5}, {56, 56, 0.5}, {8, 56, 0.5});
  const double z0 = 0.55 - penetration, z1 = z0 + 0.2;
  push_quad(tilted, {16, 20, z0}, {48, 20, z1}, {48, 44, z1}, {16, 44, z0});
  scene.draws.push_back(pixel_triangles(scene, tilted));  // behind first, as a scene would list it
  scene.draws.push_back(pixel_triangles(scene, front));
  return scene;
}

Scene make_near_w_line(float w) {
  Scene scene = window_scene("near_w_line");
  Draw draw;
  draw.topology = Topology::LineList;
  draw.positions_clip = {{-0.7f, -0.6f, 0.5f, 1}, {0.2f, 0.6f, 0.0f, w}};
  scene.draws.push_back(draw);
  return scene;
}

Scene make_near_cross_triangle(double behind) {
  Scene scene = window_scene("near_cross_triangle");
  Draw draw;
  draw.positions_clip = {{-0.6f, -0.7f, 0.5f, 1}, {0.7f, -0.5f, 0.5f, 1}, {0.2f, 0.6f, float(-behind), 1}};
  scene.draws.push_back(draw);
  return scene;
}

Scene make_near_cross_line(double behind) {
  Scene scene = window_scene("near_cross_line");
  Draw draw;
  draw.topology = Topology::LineList;
  draw.positions_clip = {{-0.7f, -0.6f, 0.5f, 1}, {0.2f, 0.6f, float(-behind), 1}};
  scene.draws.push_back(draw);
  return scene;
}

namespace {

Scene map_line(const char* name, LineMode mode, glm::dvec2 p0, glm::dvec2 p1) {
  Scene scene = window_scene(name);
  scene.width = 272;
  scene.height = 96;
  Draw draw = pixel_triangles(scene, {{p0.x, p0.y, 0.5}, {p1.x, p1.y, 0.5}});
  draw.topology = Topology::LineList;
  draw.state.line_mode = mode;
  draw.state.depth.test_enable = false;
  draw.state.depth.write_enable = false;
  scene.draws.push_back(draw);
  return scene;
}

constexpr glm::dvec2 kLineStart{8.5, 8.5};

}  // namespace

glm::dvec2 line_slope_run(double angle_deg) {
  const double a = angle_deg * std::numbers::pi / 180;
  return {std::round(40 * std::cos(a)), std::round(40 * std::sin(a))};
}

glm::dvec2 line_length_run(double length_px) { return {length_px, std::round(length_px / 3)}; }

Scene make_line_slope(LineMode mode, double angle_deg) {
  return map_line("line_slope", mode, kLineStart, kLineStart + line_slope_run(angle_deg));
}

Scene make_line_end_offset(LineMode mode, double offset_px) {
  return map_line("line_end_offset", mode, kLineStart,
                  kLineStart + glm::dvec2(kLineOffsetRun, kLineOffsetRise + offset_px));
}

Scene make_line_length(LineMode mode, double length_px) {
  return map_line("line_length", mode, kLineStart, kLineStart + line_length_run(length_px));
}

namespace {

// The cull camera: 60-degree field of view, square frame, near 0.5, far 100; eye space looks down -z.
constexpr double kCullNear = 0.5, kCullFar = 100;
const double kCullFocal = 1 / std::tan(std::numbers::pi / 6);

glm::vec4 cull_clip(const glm::dvec3& eye) {
  const double w = -eye.z;
  return {float(kCullFocal * eye.x), float(kCullFocal * eye.y),
          float(kCullFar * (w - kCullNear) / (kCullFar - kCullNear)), float(w)};
}

constexpr double kCullDistance = 4, kCullHalfSize = 1.5;

}  // namespace

double cull_edge_on_deg(CullPlace place) { return place == CullPlace::OffAxis ? 90 - kCullOffAxisDeg : 90; }

double cull_face_pixels() { return 2 * kCullHalfSize * kCullFocal / kCullDistance * 32; }

Scene make_cull_face(CullPlace place, double angle_deg) {
  Scene scene = window_scene("cull_face");
  const bool near = place == CullPlace::NearClipped;
  const double distance = near ? 1.5 : kCullDistance, s = near ? 2.5 : kCullHalfSize;
  const double off = place == CullPlace::OffAxis ? distance * std::tan(kCullOffAxisDeg * std::numbers::pi / 180) : 0;
  const glm::dvec3 centre(off, 0, -distance);
  // Normal n = (sin a, 0, cos a): towards the eye (+z) at 0; u, v span the face, u x v = n.
  const double a = angle_deg * std::numbers::pi / 180;
  const glm::dvec3 u(std::cos(a), 0, -std::sin(a)), v(0, 1, 0);
  // Counter-clockwise in the window (y down) while the face looks at the eye.
  const glm::dvec3 corners[3] = {centre - s * u - 0.6 * s * v, centre + s * v, centre + s * u - 0.6 * s * v};
  if (place == CullPlace::YFlip)
    scene.viewport = Viewport{0, float(scene.height), float(scene.width), -float(scene.height), 0, 1};
  Draw draw;
  for (const glm::dvec3& c : corners) draw.positions_clip.push_back(cull_clip(c));
  draw.state.cull_mode = CullMode::Back;
  draw.state.front_face = FrontFace::CounterClockwise;
  scene.draws.push_back(draw);
  return scene;
}

Scene reversed_z(Scene scene, double near_plane, double far_plane) {
  scene.name += ".reversed_z";
  scene.depth_clear = 0.0f;
  for (Draw& draw : scene.draws) {
    draw.state.depth.compare_op = CompareOp::Greater;
    // w - z with z = far (w - near) / (far - near), formed in double from w (the eye distance), not
    // from the float z, whose low bits are already gone at a large far/near.
    for (glm::vec4& p : draw.positions_clip) p.z = float(near_plane * (far_plane - double(p.w)) / (far_plane - near_plane));
  }
  return scene;
}

}  // namespace rastercmp::experiments
