#include "experiments/scene_make.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/mat4x4.hpp>

#include "model/camera.hpp"

namespace rastercmp::experiments {
namespace {

using Quad = std::array<glm::vec3, 4>;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

// Two triangles of a quad (corners in order), split along 0-2 or along 1-3.
void push_quad(std::vector<glm::vec3>& out, const Quad& q, bool other_diagonal) {
  if (!other_diagonal)
    out.insert(out.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  else
    out.insert(out.end(), {q[0], q[1], q[3], q[1], q[2], q[3]});
}

// A rectangle of half-sizes hx, hy in the plane through `centre` rotated by `angle` about y.
Quad plane_rect(glm::dvec3 centre, double angle, double hx, double hy) {
  const glm::dvec3 u(std::cos(angle), 0, -std::sin(angle));
  const glm::dvec3 v(0, 1, 0);
  Quad q;
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};
  for (int i = 0; i < 4; ++i) q[size_t(i)] = glm::vec3(centre + u * (sx[i] * hx) + v * (sy[i] * hy));
  return q;
}

Draw world_draw(const std::string& name, const std::vector<glm::vec3>& positions_world, const glm::mat4& world_to_clip,
                CullMode cull) {
  Draw draw;
  draw.name = name;
  draw.state.cull_mode = cull;
  for (const glm::vec3& p : positions_world) draw.positions_clip.push_back(world_to_clip * glm::vec4(p, 1.0f));
  return draw;
}

DecalScene make_pair(const PairParams& p) {
  Camera camera;
  camera.eye = {0, 0, 0};
  camera.target = {0, 0, -1};
  camera.fov_y_degrees = 45;
  camera.far_plane = float(p.far_plane);
  camera.near_plane = float(p.far_plane / p.far_near_ratio);
  const glm::mat4 world_to_clip = camera_world_to_clip(camera, 1.0f);
  const double angle = radians(p.angle_deg);
  const glm::dvec3 centre(0, 0, -p.distance);
  const glm::dvec3 normal(std::sin(angle), 0, std::cos(angle));  // towards the eye
  std::vector<glm::vec3> base, decal;
  push_quad(base, plane_rect(centre, angle, 18 * p.scale, 18 * p.scale), false);
  const double separation = p.kind == PairKind::NearCoplanar ? p.separation : 0.0;
  push_quad(decal, plane_rect(centre + normal * separation, angle, 12 * p.scale, 10 * p.scale), true);
  if (p.kind == PairKind::Identical) {
    base.resize(3);
    decal = base;
  }
  DecalScene out;
  out.scene.name = std::string("experiments.") + to_string(p.kind);
  out.scene.depth_format = p.format;
  out.scene.draws.push_back(world_draw("base", base, world_to_clip, CullMode::None));
  out.scene.draws.push_back(world_draw("decal", decal, world_to_clip, CullMode::None));
  out.scene.draws[1].state.depth_bias = p.decal_bias;
  out.decal_draw = 1;
  if (p.jitter_x_px != 0 || p.jitter_y_px != 0)
    for (Draw& draw : out.scene.draws)
      for (glm::vec4& clip : draw.positions_clip) {  // window x = (x/w + 1) width / 2
        clip.x = float(clip.x + 2 * p.jitter_x_px / out.scene.width * clip.w);
        clip.y = float(clip.y + 2 * p.jitter_y_px / out.scene.height * clip.w);
      }
  return out;
}

double halton_radical_inverse(int index, int base) {
  double result = 0, f = 1;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    result += f * (i % base);
  }
  return result;
}

// The lecture's house: walls z 30..54, x 0..16, y 0..10, roof ridge at y 16 (scenes/house/*.json).
std::vector<glm::vec3> house_triangles() {
  std::vector<glm::vec3> t;
  const auto quad = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) { push_quad(t, {a, b, c, d}, false); };
  quad({0, 0, 54}, {16, 0, 54}, {16, 10, 54}, {0, 10, 54});     // front (facing +z)
  t.insert(t.end(), {{0, 10, 54}, {16, 10, 54}, {8, 16, 54}});  // front gable
  quad({16, 0, 30}, {0, 0, 30}, {0, 10, 30}, {16, 10, 30});     // back
  t.insert(t.end(), {{16, 10, 30}, {0, 10, 30}, {8, 16, 30}});  // back gable
  quad({16, 0, 54}, {16, 0, 30}, {16, 10, 30}, {16, 10, 54});   // right wall
  quad({0, 0, 30}, {0, 0, 54}, {0, 10, 54}, {0, 10, 30});       // left wall
  quad({0, 0, 30}, {16, 0, 30}, {16, 0, 54}, {0, 0, 54});       // floor
  quad({16, 10, 54}, {16, 10, 30}, {8, 16, 30}, {8, 16, 54});   // right roof
  quad({0, 10, 54}, {8, 16, 54}, {8, 16, 30}, {0, 10, 30});     // left roof
  return t;
}

std::vector<glm::vec3> door_and_windows() {
  std::vector<glm::vec3> t;
  const auto rect = [&](float x0, float y0, float x1, float y1) {
    push_quad(t, {glm::vec3{x0, y0, 54}, {x1, y0, 54}, {x1, y1, 54}, {x0, y1, 54}}, false);
  };
  rect(6.5f, 0, 9.5f, 6);
  rect(1.5f, 5, 4.5f, 8);
  rect(11.5f, 5, 14.5f, 8);
  return t;
}

DecalScene make_house(const PairParams& p) {
  Camera camera;  // scenes/house/far_75.json, orbited about the target's vertical axis
  const glm::dvec3 target(8, 8, 42), eye0(20, 18, 82);
  const double orbit = radians(p.angle_deg - 45.0);
  const glm::dvec3 arm = eye0 - target;
  const glm::dvec3 arm_rotated(arm.x * std::cos(orbit) + arm.z * std::sin(orbit), arm.y,
                               -arm.x * std::sin(orbit) + arm.z * std::cos(orbit));
  camera.eye = glm::vec3(target + arm_rotated);
  camera.target = glm::vec3(target);
  camera.fov_y_degrees = 45;
  camera.far_plane = 75;
  camera.near_plane = float(75.0 / p.far_near_ratio);
  const glm::mat4 world_to_clip = camera_world_to_clip(camera, 1.0f);
  DecalScene out;
  out.scene.name = "experiments.house";
  out.scene.width = out.scene.height = 128;
  out.scene.depth_format = p.format;
  out.scene.draws.push_back(world_draw("house", house_triangles(), world_to_clip, CullMode::Back));
  out.scene.draws.push_back(world_draw("door_and_windows", door_and_windows(), world_to_clip, CullMode::Back));
  out.scene.draws[1].state.depth_bias = p.decal_bias;
  out.decal_draw = 1;
  return out;
}

Draw pixel_draw(const Viewport& viewport, const std::vector<glm::vec4>& positions_pixels) {
  Draw draw;
  for (const glm::vec4& p : positions_pixels) draw.positions_clip.push_back(pixels_to_clip(viewport, p));
  return draw;
}

}  // namespace

const char* to_string(PairKind kind) {
  switch (kind) {
    case PairKind::Coplanar: return "coplanar";
    case PairKind::NearCoplanar: return "near_coplanar";
    case PairKind::House: return "house";
    case PairKind::Identical: return "identical";
  }
  return "?";
}

DecalScene make_decal_scene(const PairParams& params) {
  return params.kind == PairKind::House ? make_house(params) : make_pair(params);
}

const char* mapping_suffix(DepthMapping mapping) {
  switch (mapping) {
    case DepthMapping::StandardFloat: return "";
    case DepthMapping::StandardDouble: return "_double_z";
    case DepthMapping::ReversedFloat: return "_reversed_z_float";
    case DepthMapping::ReversedDouble: return "_reversed_z";
  }
  return "?";
}

const char* mapping_name(DepthMapping mapping) {
  switch (mapping) {
    case DepthMapping::StandardFloat: return "standard, float clip z";
    case DepthMapping::StandardDouble: return "standard, double clip z";
    case DepthMapping::ReversedFloat: return "reversed, float clip z";
    case DepthMapping::ReversedDouble: return "reversed, double clip z";
  }
  return "?";
}

DepthMapping case_depth_mapping(const std::string& case_name) {
  DepthMapping found = DepthMapping::StandardFloat;
  size_t longest = 0;
  for (DepthMapping m : kDepthMappings) {
    const std::string suffix = mapping_suffix(m);
    if (suffix.size() > longest && case_name.size() > suffix.size() &&
        case_name.compare(case_name.size() - suffix.size(), suffix.size(), suffix) == 0)
      found = m, longest = suffix.size();
  }
  return found;
}

std::string case_depth_format(const std::string& case_name) {
  return case_name.substr(0, case_name.size() - std::string(mapping_suffix(case_depth_mapping(case_name))).size());
}

bool is_reversed(DepthMapping mapping) {
  return mapping == DepthMapping::ReversedFloat || mapping == DepthMapping::ReversedDouble;
}

Scene with_depth_mapping(Scene scene, DepthMapping mapping, double near_plane, double far_plane) {
  const double n = near_plane, f = far_plane;
  // z = A z_eye + B with z_eye = -w: standard A = -f / (f - n), B = -f n / (f - n); reversed
  // A = n / (f - n), B = n f / (f - n).
  const bool reversed = is_reversed(mapping);
  const float a = float(reversed ? n / (f - n) : -f / (f - n)), b = float(reversed ? n * f / (f - n) : -f * n / (f - n));
  if (mapping == DepthMapping::StandardFloat) return scene;
  if (reversed) {
    scene.name += mapping_suffix(mapping);
    scene.depth_clear = 0.0f;
  }
  for (Draw& draw : scene.draws) {
    if (reversed) draw.state.depth.compare_op = CompareOp::Greater;
    for (glm::vec4& p : draw.positions_clip) {
      const double w = p.w;
      if (mapping == DepthMapping::StandardDouble) p.z = float(f * (w - n) / (f - n));
      if (mapping == DepthMapping::ReversedDouble) p.z = float(n * (f - w) / (f - n));
      if (mapping == DepthMapping::ReversedFloat) {
        const float product = a * -p.w;  // rounded before the sum, as a matrix product without FMA
        p.z = product + b;
      }
    }
  }
  return scene;
}

Jitter ensemble_jitter(int j) { return j == 0 ? Jitter{} : Jitter{halton_radical_inverse(j, 2), halton_radical_inverse(j, 3), halton_radical_inverse(j, 5)}; }

Scene decal_only(const DecalScene& decal) {
  Scene scene = decal.scene;
  scene.draws = {decal.scene.draws[decal.decal_draw]};
  scene.draws[0].state.depth.test_enable = false;
  return scene;
}

Scene make_flat_plane(DepthFormat format, const DepthBias& bias) {
  Scene scene;
  scene.name = "experiments.flat_plane";
  scene.depth_format = format;
  Draw draw;
  // Window depth 0.375: away from a half-way point of the UNORM grids (0.375 * (2^n - 1) ends in
  // .625 for n = 16 and 24), so the biased depth does not sit on a rounding tie; D32's
  // r = 2^(e-23) with e = -2 (docs/lavapipe-rules.md §4.3).
  const float z = kFlatPlaneDepth;
  draw.positions_clip = {{-0.75f, -0.75f, z, 1}, {0.75f, -0.75f, z, 1}, {0.75f, 0.75f, z, 1},
                         {-0.75f, -0.75f, z, 1}, {0.75f, 0.75f, z, 1},  {-0.75f, 0.75f, z, 1}};
  draw.state.depth_bias = bias;
  scene.draws.push_back(draw);
  return scene;
}

Scene make_sliver_pair(double angle_deg, double length_px) {
  Scene scene;
  scene.name = "experiments.sliver_pair";
  scene.depth_format = DepthFormat::D32Sfloat;
  const Viewport viewport = scene.effective_viewport();
  const glm::dvec2 apex(6.5, 6.5);  // a pixel centre: the shared edge passes through a sample
  const double phi = radians(37.0), alpha = radians(angle_deg);
  const auto at = [&](double a, double z) {
    return glm::vec4(float(apex.x + length_px * std::cos(a)), float(apex.y + length_px * std::sin(a)), float(z), 1);
  };
  const glm::vec4 a(float(apex.x), float(apex.y), 0.25f, 1);
  scene.draws.push_back(pixel_draw(viewport, {a, at(phi, 0.5), at(phi + alpha, 0.75)}));
  scene.draws.push_back(pixel_draw(viewport, {a, at(phi + alpha, 0.75), at(phi + 2 * alpha, 0.5)}));
  return scene;
}

namespace {

struct FarTriangle {
  double far_x, left;  // window x of the far vertex, and of the viewport's left edge
  float near_x;
};

FarTriangle far_triangle(double distance_px) {
  const double far_x = std::min(distance_px, 32767.0);
  const double left = std::max(0.0, far_x - 16384.0);
  return {far_x, left, float(left + 0.37)};
}

}  // namespace

DesignTriangles far_triangle_design(double distance_px) {
  const FarTriangle f = far_triangle(distance_px);
  return {{{glm::dvec2(f.near_x, 0.3f), glm::dvec2(float(f.far_x), 1.1f), glm::dvec2(f.near_x, 3.7f)}},
          kMaxFramebufferSide,
          4};
}

Scene make_far_triangle(double distance_px) {
  Scene scene;
  scene.name = "experiments.far_triangle";
  scene.width = kMaxFramebufferSide;
  scene.height = 4;
  scene.depth_format = DepthFormat::D32Sfloat;
  const FarTriangle f = far_triangle(distance_px);
  scene.viewport = Viewport{float(f.left), -60, float(f.far_x - f.left), 128, 0, 1};
  scene.draws.push_back(pixel_draw(*scene.viewport,
                                   {{f.near_x, 0.3f, 0.2f, 1}, {float(f.far_x), 1.1f, 0.9f, 1}, {f.near_x, 3.7f, 0.4f, 1}}));
  return scene;
}

Scene make_mesh_scene(uint32_t size, uint32_t cells) {
  Camera camera;
  camera.eye = {0, 9, 14};
  camera.target = {0, 0, 0};
  camera.fov_y_degrees = 50;
  camera.near_plane = 1;
  camera.far_plane = 60;
  const glm::mat4 world_to_clip = camera_world_to_clip(camera, 1.0f);
  const auto height = [](double x, double z) { return 1.5 * std::sin(0.7 * x) * std::cos(0.5 * z); };
  std::vector<glm::vec3> triangles;
  const double extent = 10, step = 2 * extent / cells;
  for (uint32_t j = 0; j < cells; ++j)
    for (uint32_t i = 0; i < cells; ++i) {
      Quad q;
      const double xs[4] = {0, 1, 1, 0}, zs[4] = {0, 0, 1, 1};
      for (int k = 0; k < 4; ++k) {
        const double x = -extent + (i + xs[k]) * step, z = -extent + (j + zs[k]) * step;
        q[size_t(k)] = glm::vec3(float(x), float(height(x, z)), float(z));
      }
      push_quad(triangles, q, (i + j) % 2 == 1);
    }
  Scene scene;
  scene.name = "experiments.mesh";
  scene.width = scene.height = size;
  scene.draws.push_back(world_draw("mesh", triangles, world_to_clip, CullMode::None));
  return scene;
}

Scene make_line_star(uint32_t size, uint32_t lines) {
  Scene scene;
  scene.name = "experiments.line_star";
  scene.width = scene.height = size;
  const Viewport viewport = scene.effective_viewport();
  Draw draw;
  draw.topology = Topology::LineList;
  const double centre = size / 2.0 + 0.3, inner = size * 0.05, outer = size * 0.45;
  for (uint32_t i = 0; i < lines; ++i) {
    const double a = 2 * std::numbers::pi * (i + 0.37) / lines;
    const glm::vec4 from(float(centre + inner * std::cos(a)), float(centre + inner * std::sin(a)), 0.2f, 1);
    const glm::vec4 to(float(centre + outer * std::cos(a)), float(centre + outer * std::sin(a)), 0.8f, 1);
    draw.positions_clip.push_back(pixels_to_clip(viewport, from));
    draw.positions_clip.push_back(pixels_to_clip(viewport, to));
  }
  scene.draws.push_back(draw);
  return scene;
}

Scene make_near_w_triangle(float w_clip) {
  Scene scene;
  scene.name = "experiments.near_w";
  scene.depth_format = DepthFormat::D32Sfloat;
  Draw draw;
  draw.positions_clip = {{-0.6f, -0.7f, 0.5f, 1}, {0.7f, -0.5f, 0.5f, 1}, {0.2f, 0.6f, 0.0f, w_clip}};
  scene.draws.push_back(draw);
  return scene;
}

Scene make_non_finite_triangle(uint32_t component, float value) {
  Scene scene = make_near_w_triangle(1.0f);
  scene.name = "experiments.non_finite";
  Draw second;
  second.positions_clip = {{-0.9f, 0.1f, 0.3f, 1}, {0.1f, 0.9f, 0.3f, 1}, {-0.9f, 0.9f, 0.3f, 1}};
  second.positions_clip[1][int(component)] = value;
  scene.draws.push_back(second);
  return scene;
}

}  // namespace rastercmp::experiments
