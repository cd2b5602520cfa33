// explain with classic methods (cpu_raster/classic/classic_explain.hpp): at a chosen pixel of a
// scene of scenes/methods/, the method's decision and the exact path's are both printed, and the
// method's decision variables carry the values computed here independently from the scene (the
// clip positions, the window coordinates the explanation prints, the notes' loops written out).
#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "cpu_raster/classic/classic_explain.hpp"
#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "cpu_raster/exact/explain.hpp"
#include "cpu_raster/methods/clip_line_cohen_sutherland.hpp"
#include "cpu_raster/methods/line_bresenham.hpp"
#include "cpu_raster/methods/line_dda.hpp"
#include "cpu_raster/methods/visibility_bsp.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

Scene method_scene(const std::string& relative) {
  return load_scene_file(std::string(RASTERCMP_SOURCE_DIR) + "/scenes/methods/" + relative + ".json");
}

CpuOptions with_methods(std::vector<MethodChoice> methods) {
  CpuOptions options;
  options.fma = true;
  options.methods = std::move(methods);
  return options;
}

std::string g9(double v) { return fmt::format("{:.9g}", v + 0.0); }  // as explain: no "-0"
std::string g17(double v) { return fmt::format("{:.17g}", v); }

std::string owner_words(uint32_t owner) {
  if (owner == kOwnerBackground) return "background";
  return fmt::format("draw {} primitive {}", owner_draw(owner), owner_primitive(owner));
}

// Both blocks are there, each ending with its own result, and "differ:" says what the two renders
// hold at the pixel.
void expect_both_decisions(const std::string& text, const RenderResult& method, const RenderResult& exact, uint32_t x,
                           uint32_t y) {
  const size_t i = exact.index(x, y, 0);
  const size_t method_block = text.find("method (judged): classic path, methods");
  const size_t exact_block = text.find("exact (reference): the exact path at the same sample");
  ASSERT_NE(method_block, std::string::npos) << text;
  ASSERT_NE(exact_block, std::string::npos) << text;
  EXPECT_LT(method_block, exact_block) << text;
  std::string method_result = "classic result: owner " + owner_words(method.owner[i]);
  std::string exact_result = "exact result: owner " + owner_words(exact.owner[i]);
  if (exact.has_depth()) {
    method_result += fmt::format(", depth raw {:#x}", method.depth_raw[i]);
    exact_result += fmt::format(", depth raw {:#x}", exact.depth_raw[i]);
  }
  EXPECT_NE(text.find(method_result + "\n"), std::string::npos) << method_result << "\n" << text;
  EXPECT_NE(text.find(exact_result + "\n"), std::string::npos) << exact_result << "\n" << text;
  if (method.owner[i] != exact.owner[i]) {
    EXPECT_NE(
        text.find("differ: owner: method " + owner_words(method.owner[i]) + ", exact " + owner_words(exact.owner[i])),
        std::string::npos)
        << text;
  } else if (!exact.has_depth() || method.depth_raw[i] == exact.depth_raw[i]) {
    EXPECT_NE(text.find("differ: nowhere at this sample (same owner and raw depth)\n"), std::string::npos) << text;
  }
}

// The first pixel in scan order where the method's owner differs from the exact path's.
std::array<uint32_t, 2> first_owner_difference(const RenderResult& method, const RenderResult& exact) {
  for (uint32_t y = 0; y < exact.height; ++y)
    for (uint32_t x = 0; x < exact.width; ++x)
      if (method.owner[method.index(x, y, 0)] != exact.owner[exact.index(x, y, 0)]) return {x, y};
  ADD_FAILURE() << "the method and the exact path agree everywhere: the scene changed";
  return {0, 0};
}

// visibility=painter on the cyclic sticks: the keys are the largest window z of each stick (its
// scene z: pixels space, depth range 0..1), the order the stable descending sort of those keys.
TEST(ExplainMethods, PainterPrintsTheSortKeysAndTheOrder) {
  const Scene scene = method_scene("visibility/painter/cyclic_sticks");
  const CpuOptions options = with_methods({{"visibility", "painter"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  const auto [x, y] = first_owner_difference(method, exact);
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);

  std::vector<double> keys;
  for (const Draw& draw : scene.draws)
    for (size_t v = 0; v + 2 < draw.positions_clip.size(); v += 3)
      keys.push_back(std::max({double(draw.positions_clip[v].z), double(draw.positions_clip[v + 1].z),
                               double(draw.positions_clip[v + 2].z)}));
  std::vector<size_t> order(keys.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return keys[a] > keys[b]; });
  // Every triangle painted at the pixel is listed with its key and its place, in painting order.
  const std::regex row("    #(\\d+) draw \\d+ primitive \\d+: key ([-0-9.e]+), painted (\\d+)\\w\\w of (\\d+)");
  size_t rows = 0, last_place = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), row), end; it != end; ++it, ++rows) {
    const size_t primitive = std::stoul((*it)[1]);
    ASSERT_LT(primitive, keys.size());
    EXPECT_EQ((*it)[2].str(), g9(keys[primitive])) << text;
    const size_t place = std::stoul((*it)[3]);
    EXPECT_EQ(order[place - 1], primitive) << text;
    EXPECT_EQ(std::stoul((*it)[4]), keys.size());
    EXPECT_GT(place, last_place) << "not in painting order\n" << text;
    last_place = place;
  }
  EXPECT_GE(rows, 2u) << "the pixel where painter fails has two sticks painted over each other\n" << text;
  EXPECT_NE(text.find("(last here: the owner)"), std::string::npos) << text;
}

// visibility=bsp: for each piece painted at the pixel the path from the root, each node's plane
// and the viewer's side of it; for the viewer (0, 0, -1, 0) that side is -n.z, and a later piece
// has a higher rank.
TEST(ExplainMethods, BspPrintsThePlaneSideTestAlongThePath) {
  const Scene scene = method_scene("visibility/bsp/interpenetrating");
  const CpuOptions options = with_methods({{"visibility", "bsp"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  // A pixel both triangles paint: the owner there is decided by the order.
  uint32_t x = 0, y = 0;
  bool found = false;
  for (uint32_t py = 0; py < scene.height && !found; ++py)
    for (uint32_t px = 0; px < scene.width && !found; ++px) {
      const std::string text = explain_classic_pixel(scene, options, px, py);
      if (std::count(text.begin(), text.end(), '\n') > 0 && text.find("painted as fragment") != std::string::npos &&
          text.find("painted as fragment") != text.rfind("painted as fragment"))
        x = px, y = py, found = true;
    }
  ASSERT_TRUE(found) << "no pixel where two pieces are painted: the scene changed";
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);
  EXPECT_NE(text.find("visibility=bsp: a tree of "), std::string::npos) << text;
  const std::regex node(
      "node (\\d+) \\(plane of #(\\d+): n \\(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\\), d ([-0-9.e]+)\\): viewer side "
      "([-0-9.e]+) (> 0, eye in front: behind drawn first|<= 0, eye behind: in front drawn first); the piece (is "
      "behind|is in front|is at this node)");
  size_t tests = 0, at_node = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), node), end; it != end; ++it, ++tests) {
    const double nz = std::stod((*it)[5]), side = std::stod((*it)[7]);
    EXPECT_EQ(g9(-nz == 0 ? 0.0 : -nz), g9(side)) << (*it)[0];
    EXPECT_EQ(side > 0, (*it)[8].str().front() == '>') << (*it)[0];
    // The node's plane is the partition triangle's: n is normal to its window-space edges (the
    // viewport is the framebuffer, depth range 0..1).
    const size_t partition = std::stoul((*it)[2]);
    const Draw& draw = scene.draws[0];
    ASSERT_LT(3 * partition + 2, draw.positions_clip.size());
    const auto window = [&](const glm::vec4& p) {
      return std::array<double, 3>{(double(p.x) / p.w + 1) * scene.width / 2,
                                   (double(p.y) / p.w + 1) * scene.height / 2, double(p.z) / p.w};
    };
    const std::array<double, 3> a = window(draw.positions_clip[3 * partition]);
    const std::array<double, 3> b = window(draw.positions_clip[3 * partition + 1]);
    const double n[3] = {std::stod((*it)[3]), std::stod((*it)[4]), nz};
    const double edge[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) *
                          std::sqrt(edge[0] * edge[0] + edge[1] * edge[1] + edge[2] * edge[2]);
    EXPECT_NEAR((n[0] * edge[0] + n[1] * edge[1] + n[2] * edge[2]) / length, 0.0, 1e-6) << (*it)[0];
    at_node += (*it)[9].str() == "is at this node";
  }
  EXPECT_GE(tests, 2u) << text;
  EXPECT_GE(at_node, 2u) << "each painted piece's path ends at its node\n" << text;
  // The ranks of the painted pieces rise in painting order, and the last is the owner.
  const std::regex rank("piece rank (\\d+) of (\\d+)");
  size_t last = 0, ranks = 0;
  for (std::sregex_iterator it(text.begin(), text.end(), rank), end; it != end; ++it, ++ranks) {
    EXPECT_GT(std::stoul((*it)[1]), last) << text;
    last = std::stoul((*it)[1]);
  }
  EXPECT_GE(ranks, 2u) << text;
}

// cull=normal_dot_view with a negative-height viewport: N·V in clip space culls the triangle the
// exact path keeps. N·V is computed here from the draw's clip positions; the exact path's signed
// area is printed beside it.
TEST(ExplainMethods, CullListsTheCulledTriangleWithNDotVAndTheExactArea) {
  const Scene scene = method_scene("cull/normal_dot_view/flipped_viewport");
  const CpuOptions options = with_methods({{"cull", "normal_dot_view"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  const auto [x, y] = first_owner_difference(method, exact);
  const uint32_t kept = exact.owner[exact.index(x, y, 0)];
  ASSERT_NE(kept, kOwnerBackground);
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);
  EXPECT_NE(text.find("cull=normal_dot_view removed near the pixel"), std::string::npos) << text;

  const Draw& draw = scene.draws[owner_draw(kept)];
  const uint32_t first = 3 * owner_primitive(kept);
  std::array<std::array<double, 3>, 3> v;
  for (size_t k = 0; k < 3; ++k) {
    const glm::vec4& p = draw.positions_clip[first + k];
    v[k] = {p.x, p.y, p.w};
  }
  const std::array<double, 3> e1{v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
  const std::array<double, 3> e2{v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
  std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  if (draw.state.front_face == FrontFace::Clockwise) n = {-n[0], -n[1], -n[2]};
  const double n_dot_v = -(n[0] * v[0][0] + n[1] * v[0][1] + n[2] * v[0][2]);
  ASSERT_LE(n_dot_v, 0) << "the kept triangle is a back face in clip space";
  const std::string culled =
      fmt::format("    {}: N ({}, {}, {}), V ({}, {}, {}), N.V = {} <= 0: back face -> culled\n", owner_words(kept),
                  g9(n[0]), g9(n[1]), g9(n[2]), g9(-v[0][0]), g9(-v[0][1]), g9(-v[0][2]), g9(n_dot_v));
  EXPECT_NE(text.find(culled), std::string::npos) << culled << text;
  // Beside it the exact path's decision, from its own explanation at the pixel.
  bool area_printed = false;
  for (const FragmentRecord& r : explain_pixel(scene, with_methods({}), x, y))
    if (encode_owner(r.draw_index, r.primitive_index) == kept && r.cull == CullReason::None)
      area_printed = text.find(fmt::format("      exact: snapped signed area (doubled, 1/256 px units) {}, {}-facing",
                                           r.fixed_area, r.front_facing ? "front" : "back")) != std::string::npos;
  EXPECT_TRUE(area_printed) << text;
}

// clip=liang_barsky on the lines crossing two framebuffer sides: the per-plane distances, the
// crossing parameters and t_in / t_out, from the clip positions (-w <= x, y <= w, 0 <= z <= w).
TEST(ExplainMethods, LiangBarskyPrintsTheCrossingsAndTInTOut) {
  const Scene scene = method_scene("clip/liang_barsky/clipped_lines");
  const CpuOptions options = with_methods({{"clip", "liang_barsky"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  // A pixel of line 1 (the second segment), which both ends of leave the framebuffer.
  const uint32_t line = encode_owner(0, 1);
  size_t at = 0;
  while (at < method.owner.size() && method.owner[at] != line) ++at;
  ASSERT_LT(at, method.owner.size()) << "line 1 is not drawn: the scene changed";
  const uint32_t x = uint32_t(at % scene.width), y = uint32_t(at / scene.width);
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);

  const glm::vec4 p0 = scene.draws[0].positions_clip[2], p1 = scene.draws[0].positions_clip[3];
  const auto distances = [](const glm::vec4& p) {
    return std::array<double, 6>{double(p.x) + p.w, double(p.w) - p.x, double(p.y) + p.w,
                                 double(p.w) - p.y, double(p.z),       double(p.w) - p.z};
  };
  const std::array<double, 6> d0 = distances(p0), d1 = distances(p1);
  static const char* kPlanes[6] = {"x >= -w", "x <= w", "y >= -w", "y <= w", "z >= 0", "z <= w"};
  double t_in = 0, t_out = 1;
  size_t crossings = 0;
  for (size_t k = 0; k < 6; ++k) {
    std::string row = fmt::format("      {}: d0 {}, d1 {}", kPlanes[k], g9(d0[k]), g9(d1[k]));
    const double t = d0[k] / (d0[k] - d1[k]);
    if (d0[k] < 0) row += fmt::format(", entering at t = d0 / (d0 - d1) = {} (raises t_in)", g9(t)), ++crossings;
    if (d1[k] < 0) row += fmt::format(", leaving at t = d0 / (d0 - d1) = {} (lowers t_out)", g9(t)), ++crossings;
    if (d0[k] >= 0 && d1[k] >= 0) row += ", both ends inside";
    EXPECT_NE(text.find(row + "\n"), std::string::npos) << row << "\n" << text;
    if (d0[k] < 0) t_in = std::max(t_in, t);
    if (d1[k] < 0) t_out = std::min(t_out, t);
  }
  EXPECT_EQ(crossings, 4u) << "each end is outside two planes (a corner beyond each of two sides)";
  EXPECT_GT(t_in, 0);
  EXPECT_LT(t_out, 1);
  EXPECT_NE(text.find(fmt::format("      -> t_in {}, t_out {} ", g9(t_in), g9(t_out))), std::string::npos) << text;
  EXPECT_NE(text.find("clip=liang_barsky: clip-space outcodes p0 "), std::string::npos) << text;
}

// line=dda at the last pixel of a line with both ends inside: the method plots it, the exact
// diamond-exit rule does not. The accumulated y at that column is the notes' loop run here.
TEST(ExplainMethods, DdaPrintsTheAccumulatedCoordinateAndItsRounding) {
  const Scene scene = method_scene("line/dda/inside_endpoints");
  const CpuOptions options = with_methods({{"line", "dda"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  // Line 0 runs from pixel (3, 4) to pixel (27, 11): x-major, slope 7/24.
  const uint32_t x = 27, y = 11;
  ASSERT_EQ(method.owner[method.index(x, y, 0)], encode_owner(0, 0));
  ASSERT_EQ(exact.owner[exact.index(x, y, 0)], kOwnerBackground);
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);
  EXPECT_NE(text.find("differ: owner: method draw 0 primitive 0, exact background"), std::string::npos) << text;

  const double slope = 7.0 / 24.0;
  double accumulated = 4;
  for (int step = 0; step < 24; ++step) accumulated += slope;
  EXPECT_NE(text.find(fmt::format("DDA steps along x (+1 per step), y += {} per step", g17(slope))), std::string::npos)
      << text;
  EXPECT_NE(text.find(fmt::format("at x = 27 (step 24): y = {} (accumulated; 4 + 24 x slope = {}), floor({}) = 11",
                                  g17(accumulated), g17(4 + 24 * slope), g17(accumulated + 0.5))),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("this pixel is step 24 -> covered"), std::string::npos) << text;
  // Beside it, lavapipe's line planes at the same pixel: not covered.
  EXPECT_NE(text.find("    exact: lavapipe's line planes, E "), std::string::npos) << text;
  EXPECT_NE(text.substr(text.find("    exact: lavapipe's line planes")).find("-> not covered"), std::string::npos)
      << text;
}

// line=bresenham: the error term at the pixel's column, by the notes' complete version run here.
TEST(ExplainMethods, BresenhamPrintsTheErrorTermAtTheStep) {
  const Scene scene = method_scene("line/bresenham/inside_endpoints");
  const CpuOptions options = with_methods({{"line", "bresenham"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  // Line 0 runs from pixel (3, 4) to pixel (27, 11): deltax 24, deltay 7; column 15 is step 12.
  const uint32_t x = 15;
  int64_t error = 0, minor = 4, y = 0, before = 0, added = 0;
  bool stepped = false;
  for (int64_t column = 3; column <= int64_t(x); ++column) {
    y = minor, before = error, error += 7, added = error, stepped = 2 * error >= 24;
    if (stepped) ++minor, error -= 24;
  }
  ASSERT_EQ(method.owner[method.index(x, uint32_t(y), 0)], encode_owner(0, 0));
  const std::string text = explain_classic_pixel(scene, options, x, uint32_t(y));
  expect_both_decisions(text, method, exact, x, uint32_t(y));
  EXPECT_NE(text.find("deltax 24, deltay 7, ystep 1"), std::string::npos) << text;
  EXPECT_NE(text.find(fmt::format("at x = 15 (step 12): plotted y {} with error {}; error + deltay = {}, 2 error = {}{}"
                                  "deltax 24: {}, error {}\n",
                                  y, before, added, 2 * added, stepped ? " >= " : " < ",
                                  stepped ? "the minor axis steps" : "no step", error)),
            std::string::npos)
      << text;
}

// depth=perspective_correct: the window-space barycentrics of the pixel centre and 1/w there,
// from the window coordinates and w the explanation prints for the triangle.
TEST(ExplainMethods, PerspectiveCorrectPrintsLambdaAndOneOverW) {
  const Scene scene = method_scene("depth/perspective_correct/varying_w");
  const CpuOptions options = with_methods({{"depth", "perspective_correct"}});
  const RenderResult method = render_classic(scene, options);
  const RenderResult exact = render_cpu(scene, with_methods({}));
  size_t at = 0;
  while (at < method.depth_raw.size() && method.depth_raw[at] == exact.depth_raw[at]) ++at;
  ASSERT_LT(at, method.depth_raw.size()) << "the 1/w weighting changes no depth: the scene changed";
  const uint32_t x = uint32_t(at % scene.width), y = uint32_t(at / scene.width);
  const std::string text = explain_classic_pixel(scene, options, x, y);
  expect_both_decisions(text, method, exact, x, y);
  EXPECT_NE(
      text.find(fmt::format("differ: depth raw: method {:#x}, exact {:#x}", method.depth_raw[at], exact.depth_raw[at])),
      std::string::npos)
      << text;
  // The owner's triangle as printed: window (x, y, z, w) per vertex, then its depth line.
  const std::regex triangle(
      "triangle, window \\(([-0-9.e]+), ([-0-9.e]+), z ([-0-9.e]+), w ([-0-9.e]+)\\) \\(([-0-9.e]+), ([-0-9.e]+), z "
      "([-0-9.e]+), w ([-0-9.e]+)\\) \\(([-0-9.e]+), ([-0-9.e]+), z ([-0-9.e]+), w ([-0-9.e]+)\\)\n(?:.*\n)*?    "
      "depth=perspective_correct: at the pixel centre lambda \\(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\\), 1/w of the "
      "vertices \\(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\\), 1/w at the sample = sum lambda/w = ([-0-9.e]+)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(text, m, triangle)) << text;
  double px[3], py[3], w[3];
  for (size_t k = 0; k < 3; ++k) {
    px[k] = std::stod(m[1 + 4 * k]), py[k] = std::stod(m[2 + 4 * k]), w[k] = std::stod(m[4 + 4 * k]);
  }
  const double cx = x + 0.5, cy = y + 0.5;
  const double area = (px[1] - px[0]) * (py[2] - py[0]) - (py[1] - py[0]) * (px[2] - px[0]);
  const double l1 = ((cx - px[0]) * (py[2] - py[0]) - (cy - py[0]) * (px[2] - px[0])) / area;
  const double l2 = ((px[1] - px[0]) * (cy - py[0]) - (py[1] - py[0]) * (cx - px[0])) / area;
  const double lambda[3] = {1 - l1 - l2, l1, l2};
  double inv_w = 0;
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(std::stod(m[13 + k]), lambda[k], 1e-6) << k << "\n" << text;
    EXPECT_NEAR(std::stod(m[16 + k]), 1 / w[k], 1e-6 / w[k]) << k << "\n" << text;
    inv_w += lambda[k] / w[k];
  }
  EXPECT_NEAR(std::stod(m[19]), inv_w, 1e-6 * inv_w) << text;
  EXPECT_GT(std::abs(w[0] - w[1]) + std::abs(w[1] - w[2]), 0.0) << "w varies across the triangle";
}

// The traces explain prints are the methods' own steps: the same pixels, passes and order.
TEST(ExplainMethods, TracesAreTheMethodsOwnSteps) {
  for (const auto& [p0, p1] : std::vector<std::pair<methods::PixelXY, methods::PixelXY>>{
           {{3, 4}, {27, 11}}, {{0, 0}, {2, -1}}, {{5, 28}, {25, 16}}, {{28, 29}, {28, 20}}, {{7, 7}, {7, 7}}}) {
    std::vector<methods::PixelXY> dda, bresenham;
    for (const methods::DdaStep& step : methods::line_dda_trace(p0, p1).steps) dda.push_back(step.pixel);
    for (const methods::BresenhamStep& step : methods::line_bresenham_trace(p0, p1).steps)
      bresenham.push_back(step.pixel);
    EXPECT_EQ(dda, methods::line_dda(p0, p1));
    EXPECT_EQ(bresenham, methods::line_bresenham(p0, p1));
  }
  // A segment leaving the window on two sides: one row per pass, the last one accepting.
  const methods::CohenSutherlandResult cs =
      methods::clip_line_cohen_sutherland({{-2, 1}, {3, 7}}, methods::Rect2{0, 0, 4, 5});
  ASSERT_EQ(cs.trace.size(), size_t(cs.passes));
  EXPECT_EQ(cs.clips, int(std::count_if(cs.trace.begin(), cs.trace.end(),
                                        [](const methods::CohenSutherlandPass& p) { return p.clipped; })));
  ASSERT_TRUE(cs.accepted);
  EXPECT_EQ(cs.trace.back().code_p0 | cs.trace.back().code_p1, 0);
  EXPECT_FALSE(cs.trace.back().clipped);
  EXPECT_TRUE(cs.trace.front().clipped);
  // BSP: the polygons in back-to-front order are the nodes' in bsp_node_order.
  std::vector<methods::Polygon3> polygons;
  for (uint32_t i = 0; i < 4; ++i)
    polygons.push_back({{{0, double(i), double(i)}, {4, double(i), 4 - double(i)}, {0, double(i) + 3, 2}}, i});
  const methods::BspTree tree = methods::build_bsp(polygons);
  std::vector<uint32_t> by_nodes, by_order;
  for (int32_t node : methods::bsp_node_order(tree, {0, 0, -1, 0}))
    for (const methods::Polygon3& piece : tree.nodes[size_t(node)].polygons) by_nodes.push_back(piece.id);
  for (const methods::Polygon3& piece : methods::bsp_back_to_front(tree, {0, 0, -1, 0})) by_order.push_back(piece.id);
  EXPECT_EQ(by_nodes, by_order);
  EXPECT_EQ(by_order.size(), polygons.size() + tree.splits);
}

// The same question gives the same bytes.
TEST(ExplainMethods, SameInputSameText) {
  const Scene scene = method_scene("visibility/painter/cyclic_sticks");
  const CpuOptions options = with_methods({{"visibility", "painter"}});
  EXPECT_EQ(explain_classic_pixel(scene, options, 16, 16), explain_classic_pixel(scene, options, 16, 16));
}

}  // namespace
}  // namespace rastercmp
