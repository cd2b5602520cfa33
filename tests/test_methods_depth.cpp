// Depth methods: the notes' bilinear interpolation, perspective-correct interpolation, the depth
// plane evaluated without fused multiply-add, and the notes' pseudo-depth.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <stdexcept>

#include "cpu_raster/methods/depth_bilinear.hpp"
#include "cpu_raster/methods/depth_plane.hpp"
#include "cpu_raster/methods/interp_perspective.hpp"
#include "cpu_raster/methods/pseudo_depth.hpp"

namespace m = rastercmp::methods;
using m::Vec2;
using m::Vec3;

namespace {

rc::Gen<double> coordinate(double lo, double hi) {
  return rc::gen::map(rc::gen::resize(100, rc::gen::inRange<int64_t>(0, int64_t(1) << 20)),
                      [=](int64_t k) { return lo + (hi - lo) * double(k) / double(int64_t(1) << 20); });
}

// The plane through three (x, y, f) points, evaluated at p (Cramer's rule).
double plane_value(const std::array<Vec3, 3>& t, Vec2 p) {
  const std::array<Vec2, 3> xy{{{t[0].x, t[0].y}, {t[1].x, t[1].y}, {t[2].x, t[2].y}}};
  return m::interpolate_linear(m::barycentric_window(xy, p), {t[0].z, t[1].z, t[2].z});
}

// A perspective projection: eye space (camera at the origin looking down -z) to clip w = -z and
// window x = x / w, y = y / w.
struct Projected {
  Vec2 pos_window;
  double w_clip;
};
Projected project(Vec3 pos_eye) { return {{pos_eye.x / -pos_eye.z, pos_eye.y / -pos_eye.z}, -pos_eye.z}; }

}  // namespace

// lecture-depth-clipping-polygon-offset.txt "Interpolation - Y" and "Interpolation - X":
// Q1 = (4,2,0.5), Q2 = (1,7,1) at y = 5 give f(R1) = 3/5 + 1/5 = 0.8; Q3 = (7,4,0), Q4 = (1,7,1)
// give f(R2) = 1/3 ("~ 0.3"); then R1 = (2,4,0.8), R2 = (6,5,0.3) at x = 3 give 0.675.
TEST(MethodsDepth, NotesBilinearExample) {
  EXPECT_NEAR(m::lerp_edge_at_y({4, 2, 0.5}, {1, 7, 1}, 5), 0.8, 1e-15);
  EXPECT_NEAR(m::lerp_edge_at_y({7, 4, 0}, {1, 7, 1}, 5), 1.0 / 3.0, 1e-15);
  EXPECT_NEAR(m::lerp_span_at_x({2, 4, 0.8}, {6, 5, 0.3}, 3), 0.675, 1e-15);
}

// The notes round f(R2) to 0.3 and place R1, R2 at x = 2 and 6; on the edges themselves they lie
// at x = 2.2 and x = 5 (y = 5), and the unrounded composition is the triangle's plane value 2/3.
TEST(MethodsDepth, NotesTriangleWithoutRounding) {
  EXPECT_NEAR(m::edge_x_at_y({4, 2, 0.5}, {1, 7, 1}, 5), 2.2, 1e-15);
  EXPECT_NEAR(m::edge_x_at_y({7, 4, 0}, {1, 7, 1}, 5), 5.0, 1e-15);
  const std::array<Vec3, 3> triangle{{{4, 2, 0.5}, {1, 7, 1}, {7, 4, 0}}};
  const std::optional<double> depth = m::bilinear_depth_in_triangle(triangle, {3, 5});
  ASSERT_TRUE(depth.has_value());
  EXPECT_NEAR(*depth, 2.0 / 3.0, 1e-15);
  EXPECT_NEAR(plane_value(triangle, {3, 5}), 2.0 / 3.0, 1e-15);
  EXPECT_FALSE(m::bilinear_depth_in_triangle(triangle, {0, 5}).has_value());  // left of the edge
  EXPECT_FALSE(m::bilinear_depth_in_triangle(triangle, {3, 8}).has_value());  // above the top vertex
  EXPECT_DOUBLE_EQ(*m::bilinear_depth_in_triangle(triangle, {1, 7}), 1.0);    // the top vertex
}

// lecture-clipping-fill-zbuffer.txt "pz At near and far": pz(near) = 1, pz(far) = -1, with the
// notes' near = -25 and far = -75, -750, -7500; "What if you Want Depth?": the inverse.
TEST(MethodsDepth, NotesPseudoDepth) {
  for (double far : {-75.0, -750.0, -7500.0}) {
    EXPECT_DOUBLE_EQ(m::pseudo_depth(-25, -25, far), 1.0) << far;
    EXPECT_DOUBLE_EQ(m::pseudo_depth(far, -25, far), -1.0) << far;
    EXPECT_DOUBLE_EQ(m::eye_z_from_pseudo_depth(1.0, -25, far), -25.0) << far;
    EXPECT_DOUBLE_EQ(m::eye_z_from_pseudo_depth(-1.0, -25, far), far) << far;
  }
  // Not linear ("More precision for objects closer to the near plane"): half-way in depth (-50)
  // already spends three quarters of the range; with far = -7500 the 25 units past near spend half.
  EXPECT_NEAR(m::pseudo_depth(-50, -25, -75), -0.5, 1e-12);
  EXPECT_NEAR(m::pseudo_depth(-50, -25, -7500), 0.0, 0.005);
  EXPECT_THROW(m::pseudo_depth(-30, -25, -25), std::invalid_argument);
  EXPECT_THROW(m::pseudo_depth(0, -25, -75), std::invalid_argument);
}

// Attributes need the 1/w correction; linear interpolation in window space gets them wrong.
TEST(MethodsDepth, PerspectiveCorrectRecoversTheSurfacePoint) {
  const std::array<Vec3, 3> eye{{{-1, -1, -2}, {3, -1, -10}, {-1, 2, -4}}};
  const std::array<double, 3> u{0, 1, 0.25};        // e.g. a texture coordinate per vertex
  const std::array<double, 3> beta{0.2, 0.5, 0.3};  // a point of the 3D triangle
  const Vec3 point = eye[0] * beta[0] + eye[1] * beta[1] + eye[2] * beta[2];
  const double u_true = beta[0] * u[0] + beta[1] * u[1] + beta[2] * u[2];
  std::array<Vec2, 3> window;
  std::array<double, 3> w;
  for (size_t i = 0; i < 3; ++i) {
    window[i] = project(eye[i]).pos_window;
    w[i] = project(eye[i]).w_clip;
  }
  const std::array<double, 3> l = m::barycentric_window(window, project(point).pos_window);
  EXPECT_NEAR(m::interpolate_perspective(l, u, w), u_true, 1e-12);
  EXPECT_GT(std::fabs(m::interpolate_linear(l, u) - u_true), 0.05);
}

// Depth z/w is affine in window space: linear interpolation of z_ndc is exact (and the 1/w form
// is not), which is why depth is interpolated linearly and the notes' bilinear pseudo-depth works.
RC_GTEST_PROP(MethodsDepthProperty, LinearInterpolationIsRightForDepth, ()) {
  std::array<Vec3, 3> eye;
  for (Vec3& v : eye) v = {*coordinate(-5, 5), *coordinate(-5, 5), *coordinate(-50, -1)};
  const double b0 = *coordinate(0.05, 1), b1 = *coordinate(0.05, 1), b2 = *coordinate(0.05, 1);
  const double sum = b0 + b1 + b2;
  const Vec3 point = eye[0] * (b0 / sum) + eye[1] * (b1 / sum) + eye[2] * (b2 / sum);
  std::array<Vec2, 3> window;
  std::array<double, 3> w, pseudo;
  for (size_t i = 0; i < 3; ++i) {
    window[i] = project(eye[i]).pos_window;
    w[i] = project(eye[i]).w_clip;
    pseudo[i] = m::pseudo_depth(eye[i].z, -1, -60);
  }
  const double area = m::cross(window[1] - window[0], window[2] - window[0]);
  RC_PRE(std::fabs(area) > 1e-3);
  const std::array<double, 3> l = m::barycentric_window(window, project(point).pos_window);
  const double expected = m::pseudo_depth(point.z, -1, -60);
  RC_ASSERT(std::fabs(m::interpolate_linear(l, pseudo) - expected) < 1e-8);
  // The notes' bilinear scheme is the same plane.
  const std::array<Vec3, 3> triangle{{{window[0].x, window[0].y, pseudo[0]},
                                      {window[1].x, window[1].y, pseudo[1]},
                                      {window[2].x, window[2].y, pseudo[2]}}};
  const std::optional<double> bilinear = m::bilinear_depth_in_triangle(triangle, project(point).pos_window);
  if (bilinear) RC_ASSERT(std::fabs(*bilinear - expected) < 1e-6);
}

// Edges then across equals the plane through the three vertices, anywhere inside.
RC_GTEST_PROP(MethodsDepthProperty, BilinearEqualsPlane, ()) {
  std::array<Vec3, 3> t;
  for (Vec3& v : t) v = {*coordinate(0, 64), *coordinate(0, 64), *coordinate(0, 1)};
  const double area = m::cross(Vec2{t[1].x - t[0].x, t[1].y - t[0].y}, Vec2{t[2].x - t[0].x, t[2].y - t[0].y});
  RC_PRE(std::fabs(area) > 1);
  const double b0 = *coordinate(0.01, 1), b1 = *coordinate(0.01, 1), b2 = *coordinate(0.01, 1);
  const double sum = b0 + b1 + b2;
  const Vec2 p{(t[0].x * b0 + t[1].x * b1 + t[2].x * b2) / sum, (t[0].y * b0 + t[1].y * b1 + t[2].y * b2) / sum};
  const std::optional<double> depth = m::bilinear_depth_in_triangle(t, p);
  RC_ASSERT(depth.has_value());
  RC_ASSERT(std::fabs(*depth - plane_value(t, p)) < 1e-9);
}

RC_GTEST_PROP(MethodsDepthProperty, PseudoDepthRoundTrip, ()) {
  const double near_z = -*coordinate(0.1, 10), far_z = near_z - *coordinate(1, 1000);
  const double z = *coordinate(far_z, near_z);
  const double pz = m::pseudo_depth(z, near_z, far_z);
  RC_ASSERT(pz >= -1 - 1e-12 && pz <= 1 + 1e-12);
  RC_ASSERT(std::fabs(m::eye_z_from_pseudo_depth(pz, near_z, far_z) - z) < 1e-9 * std::fabs(far_z));
  // Nearer (larger z, still inside the range: a step of 1e-3 of the range from z could pass the near
  // plane and the eye, where pseudo-depth diverges) is larger pseudo-depth: the notes' z-buffer
  // keeps the larger value.
  const double nearer = z + 1e-3 * (near_z - z);
  if (near_z - z > 1e-6 * (near_z - far_z)) RC_ASSERT(m::pseudo_depth(nearer, near_z, far_z) > pz);
}

// The plane set-up reproduces the vertices at their pixel centres.
TEST(MethodsDepth, DepthPlaneThroughTheVertices) {
  const std::array<m::Vec3f, 3> tri{{{2.5f, 3.5f, 0.25f}, {60.5f, 10.5f, 0.75f}, {20.5f, 50.5f, 0.5f}}};
  const m::DepthPlane plane = m::setup_depth_plane(tri);
  EXPECT_NEAR(m::eval_depth_unfused(plane, 2, 3), 0.25f, 1e-6f);
  EXPECT_NEAR(m::eval_depth_unfused(plane, 60, 10), 0.75f, 1e-6f);
  EXPECT_NEAR(m::eval_depth_unfused(plane, 20, 50), 0.5f, 1e-6f);
}

// Without fusing each step rounds on its own: over a 64 x 64 grid the unfused and fused
// evaluations differ on some pixels, by no more than a few float steps, and both stay within a
// few steps of the exact plane value.
TEST(MethodsDepth, UnfusedEvaluationDiffersFromFused) {
  const std::array<m::Vec3f, 3> tri{{{0.3f, 0.7f, 0.1f}, {63.1f, 5.9f, 0.93f}, {9.7f, 61.3f, 0.47f}}};
  const m::DepthPlane plane = m::setup_depth_plane(tri);
  int differing = 0;
  for (int32_t py = 0; py < 64; ++py) {
    for (int32_t px = 0; px < 64; ++px) {
      const float unfused = m::eval_depth_unfused(plane, px, py), fused = m::eval_depth_fused(plane, px, py);
      const double exact = double(plane.a0) + double(plane.dzdx) * px + double(plane.dzdy) * py;
      differing += unfused != fused;
      EXPECT_LE(std::fabs(double(unfused) - double(fused)), 4 * std::ldexp(1.0, -24)) << px << "," << py;
      EXPECT_LE(std::fabs(double(unfused) - exact), 4 * std::ldexp(1.0, -24)) << px << "," << py;
    }
  }
  EXPECT_GT(differing, 64) << "of 4096 pixels";
}
