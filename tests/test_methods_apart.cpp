// Telling the classic methods apart (docs/methods.md "Telling the methods apart"): for each pair of
// methods that no built-in scene used to separate, the scene of scenes/methods/ built where theory says
// they differ renders differently under the two, and for the pair that provably cannot differ
// (even-odd and non-zero winding on triangles) the renders are byte-identical on every fill scene of
// scenes/methods/ and on random triangles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

namespace fs = std::filesystem;
const fs::path kMethodScenes = fs::path(RASTERCMP_SOURCE_DIR) / "scenes" / "methods";

// The scene's own "methods" with `stage` replaced by `name`, rendered as test_classic_scenes.cpp does.
RenderResult render_with(const Scene& scene, const std::string& stage, const std::string& name) {
  CpuOptions options;
  options.fma = true;
  for (const MethodChoice& choice : scene.methods)
    if (choice.stage != stage) options.methods.push_back(choice);
  options.methods.push_back({stage, name});
  return render_classic(scene, options);
}

struct Difference {
  size_t owner = 0, depth = 0;
  size_t samples = 0;  // samples where the owner or the raw depth differs
};

Difference difference(const RenderResult& a, const RenderResult& b) {
  Difference d;
  EXPECT_EQ(a.owner.size(), b.owner.size());
  for (size_t i = 0; i < std::min(a.owner.size(), b.owner.size()); ++i) {
    const bool owner = a.owner[i] != b.owner[i];
    const bool depth = a.has_depth() && a.depth_raw[i] != b.depth_raw[i];
    d.owner += owner;
    d.depth += depth;
    d.samples += owner || depth;
  }
  return d;
}

Difference apart(const std::string& file, const std::string& stage, const std::string& a, const std::string& b) {
  const Scene scene = load_scene_file((kMethodScenes / file).string());
  const Difference d = difference(render_with(scene, stage, a), render_with(scene, stage, b));
  std::printf("%-58s %s=%s vs %s: owner %zu depth %zu samples %zu\n", scene.name.c_str(), stage.c_str(), a.c_str(),
              b.c_str(), d.owner, d.depth, d.samples);
  return d;
}

// Cohen-Sutherland 3-D computes the far end's crossing from p1 towards p0 and sets it onto the plane;
// Liang-Barsky interpolates from p0. Where the crossing's exact z is halfway between two floats the
// two double results round to neighbouring floats.
TEST(MethodsApart, CohenSutherland3dAndLiangBarskyOnAFloatTie) {
  const Difference d = apart("clip/liang_barsky/far_end_tie.json", "clip", "cohen_sutherland_3d", "liang_barsky");
  EXPECT_GT(d.samples, 0u);
  EXPECT_EQ(d.owner, 0u) << "the ends move by one float: coverage stays, depth changes";
}

// Cohen-Sutherland sets the cut coordinate exactly onto the side; Cyrus-Beck's lerp at t lands a few
// double ulps off it, and the new end's clip z (from the window-space parameter) rounds differently.
TEST(MethodsApart, CohenSutherlandAndCyrusBeckOnParametricRounding) {
  const Difference d = apart("clip/cyrus_beck/t_rounding.json", "clip", "cohen_sutherland", "cyrus_beck");
  EXPECT_GT(d.samples, 0u);
}

// x - 1/2 of the right edge is 5120.5 in 1/256 px: the two snaps differ by one sub-pixel there.
TEST(MethodsApart, RoundHalfAwayAndRoundNearestEvenOnAHalfSubPixel) {
  const Difference d = apart("snap/round_half_away/half_tie.json", "snap", "round_nearest_even", "round_half_away");
  EXPECT_GT(d.owner, 0u) << "column 20's centres change owner";
}

// The scanline fill computes a crossing on the polygon shifted by -1/2, even-odd and winding on the
// polygon itself and subtract 1/2 afterwards: at 2^-62 px right of x = 0.5 only the first keeps the offset.
TEST(MethodsApart, ScanlineAndEvenOddOnACrossingAtTheCentreOfColumnZero) {
  const Difference d = apart("fill/even_odd/centre_rounding.json", "fill", "scanline", "even_odd");
  EXPECT_EQ(d.owner, 1u) << "only pixel (0, 0) of row 0";
  EXPECT_GT(apart("fill/even_odd/centre_rounding.json", "fill", "scanline", "winding").owner, 0u);
}

// Proof in docs/methods.md: on a triangle every row has 0 or 2 crossings, of opposite direction, so the
// running winding number is +-1 exactly where the parity is odd. Byte-identical on every fill scene.
TEST(MethodsApart, EvenOddAndWindingAreIdenticalOnEveryFillScene) {
  size_t scenes = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kMethodScenes / "fill")) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene_file(entry.path().string());
    const RenderResult even_odd = render_with(scene, "fill", "even_odd");
    const RenderResult winding = render_with(scene, "fill", "winding");
    EXPECT_EQ(even_odd.owner, winding.owner) << scene.name;
    EXPECT_EQ(even_odd.depth_raw, winding.depth_raw) << scene.name;
    ++scenes;
  }
  EXPECT_GE(scenes, 17u);
}

// The same on random triangles: float vertices anywhere on and around a 48x48 framebuffer, either
// winding, some on the 1/256 grid, some on pixel centres (ties), some slivers.
TEST(MethodsApart, EvenOddAndWindingAreIdenticalOnRandomTriangles) {
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<float> coordinate(-8.0f, 56.0f);
  std::uniform_int_distribution<int> kind(0, 3);
  const auto vertex = [&](std::string& text) {
    float xy[2];
    for (float& v : xy) {
      v = coordinate(rng);
      switch (kind(rng)) {
        case 0: v = std::round(v * 256.0f) / 256.0f; break;  // on the 24.8 grid
        case 1: v = std::floor(v) + 0.5f; break;             // on a pixel centre
        default: break;                                      // any float
      }
    }
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "[%.9g, %.9g, 0.5]", double(xy[0]), double(xy[1]));
    text += buffer;
  };
  size_t covered = 0;
  for (int s = 0; s < 60; ++s) {
    std::string text = R"({"width": 48, "height": 48, "space": "pixels", "draws": [{"depth_compare": "always", "positions": [)";
    for (int v = 0; v < 3 * 8; ++v) {
      if (v) text += ", ";
      vertex(text);
    }
    text += "]}]}";
    const Scene scene = parse_scene(text, "random");
    const RenderResult even_odd = render_with(scene, "fill", "even_odd");
    const RenderResult winding = render_with(scene, "fill", "winding");
    ASSERT_EQ(even_odd.owner, winding.owner) << text;
    ASSERT_EQ(even_odd.depth_raw, winding.depth_raw) << text;
    covered += size_t(std::count_if(even_odd.owner.begin(), even_odd.owner.end(),
                                    [](uint32_t id) { return id != kOwnerBackground; }));
  }
  EXPECT_GT(covered, 0u) << "the random triangles cover something";
}

// Every fill scene of scenes/methods/ besides the one built on the rounding of a crossing at the centre
// of column 0 renders the same under the scanline fill and even-odd (the pairing and the half-open
// edges are the same; only where the shift by 1/2 rounds can they part).
TEST(MethodsApart, ScanlineAndEvenOddAgreeOnTheOtherFillScenes) {
  for (const auto& entry : fs::recursive_directory_iterator(kMethodScenes / "fill")) {
    if (entry.path().extension() != ".json" || entry.path().stem() == "centre_rounding") continue;
    const Scene scene = load_scene_file(entry.path().string());
    const Difference d = difference(render_with(scene, "fill", "scanline"), render_with(scene, "fill", "even_odd"));
    EXPECT_EQ(d.samples, 0u) << scene.name;
  }
}

}  // namespace
}  // namespace rastercmp
