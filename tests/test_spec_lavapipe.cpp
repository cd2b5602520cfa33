// The spec profile against the real driver: for every built-in scene (scenes/**/*.json), the
// coverage lavapipe produces (owner ids read back through vk_reference, validation layer on) has
// no Must sample missing and no MustNot sample covered, and its stored depth lies inside every
// Must and May sample's spec interval, i.e. the spec profile accepts lavapipe's output, except where lavapipe itself
// deviates from the specification, listed below with the reason and checked to be exactly that deviation. Prints the
// Must / May / MustNot figures of the suite. Skips only without a Vulkan device.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "model/errors.hpp"
#include "model/scene_io.hpp"
#include "test_spec_support.hpp"
#include "tests/test_vulkan_support.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp {
namespace {

namespace fs = std::filesystem;
using namespace spec_test;

// Known deviations of lavapipe from the specification that the spec profile reports; `check`
// asserts that the violations are exactly that deviation.
using DeviationCheck = void (*)(const Scene&, const std::vector<CoverageClass>&, const RenderResult&,
                                const Violations&);
struct KnownDeviation {
  const char* scene;
  const char* reason;
  DeviationCheck check;
  LavapipeRule gone_with = LavapipeRule::Count;  // the release change that removed it (Count: none has)
};
void expect_only_the_scissor_leak(const Scene& scene, const std::vector<CoverageClass>& classes, const RenderResult& vk,
                                  const Violations& v);
void expect_only_the_flushed_clip(const Scene& scene, const std::vector<CoverageClass>& classes, const RenderResult& vk,
                                  const Violations& v);
constexpr KnownDeviation kKnownDeviations[] = {
    {"rastercmp.msaa.scissor.inner",
     "docs/lavapipe-rules.md §2.5: with 4x MSAA the left/top scissor planes pass samples more than 127/256 px into the "
     "column/row just outside the scissor (violates fragops.adoc \"Scissor Test\"); gone from Mesa 25.3 (§8.6)",
     expect_only_the_scissor_leak, LavapipeRule::NoMsaaRegionLeak},
    {"rastercmp.clip.guard_band.scissor_msaa",
     "docs/lavapipe-rules.md §2.5: the same 4x MSAA scissor leak, under guard-band-sized triangles (violates "
     "fragops.adoc \"Scissor Test\"); gone from Mesa 25.3 (§8.6)",
     expect_only_the_scissor_leak, LavapipeRule::NoMsaaRegionLeak},
    {"rastercmp.clip.denormal_t",
     "docs/lavapipe-rules.md §7.10: the clipper's denormal interpolation parameter flushes to 0, so the clipped "
     "polygon "
     "loses the part beyond its inside edge (violates vertexpostproc.adoc \"Primitive Clipping\")",
     expect_only_the_flushed_clip},
};

const KnownDeviation* known_deviation(const std::string& scene_name) {
  for (const KnownDeviation& k : kKnownDeviations)
    if (scene_name == k.scene) return &k;
  return nullptr;
}

using test::missing_vulkan_reason;

std::vector<fs::path> builtin_scene_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(RASTERCMP_SOURCE_DIR) / "scenes"))
    if (entry.is_regular_file() && entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// docs/lavapipe-rules.md §2.5: the samples the MSAA scissor leak can cover, just left of or above the
// scissor: samples 1 and 3 (x offset 0.875, 0.625) of column x0 - 1, samples 2 and 3 (y offset
// 0.625, 0.875) of row y0 - 1.
bool in_msaa_scissor_leak(const Scene& scene, uint32_t x, uint32_t y, uint32_t sample) {
  const Rect2D s = scene.effective_scissor();
  const int64_t x0 = s.x, y0 = s.y, x1 = int64_t(s.x) + s.width - 1, y1 = int64_t(s.y) + s.height - 1;
  const bool column = int64_t(x) == x0 - 1 && int64_t(y) >= y0 - 1 && int64_t(y) <= y1 && (sample == 1 || sample == 3);
  const bool row = int64_t(y) == y0 - 1 && int64_t(x) >= x0 - 1 && int64_t(x) <= x1 && (sample == 2 || sample == 3);
  return column || row;
}

// Every violation of the known deviation's scene lies in the leak band, and the leak is seen.
void expect_only_the_scissor_leak(const Scene& scene, const std::vector<CoverageClass>& classes, const RenderResult& vk,
                                  const Violations& v) {
  EXPECT_EQ(v.must_missing, 0u) << describe(v);
  EXPECT_EQ(v.depth_outside, 0u) << describe(v);
  EXPECT_GT(v.must_not_covered, 0u) << "the profile should report lavapipe's scissor leak";
  for (uint32_t y = 0; y < vk.height; ++y)
    for (uint32_t x = 0; x < vk.width; ++x)
      for (uint32_t s = 0; s < vk.samples; ++s) {
        const size_t i = vk.index(x, y, s);
        if (classes[i] == CoverageClass::MustNot && vk.owner[i] != kOwnerBackground) {
          EXPECT_TRUE(in_msaa_scissor_leak(scene, x, y, s))
              << "covered MustNot sample (" << x << ", " << y << ") " << s;
        }
      }
}

// The top draw of clip/denormal_t (t = 0.5/5e37, denormal) loses samples; the bottom one (t normal)
// is whole; nothing is covered that must not be.
void expect_only_the_flushed_clip(const Scene&, const std::vector<CoverageClass>& classes, const RenderResult& vk,
                                  const Violations& v) {
  EXPECT_EQ(v.must_not_covered, 0u) << describe(v);
  EXPECT_EQ(v.depth_outside, 0u) << describe(v);
  EXPECT_GT(v.must_missing, 0u) << "the profile should report the samples lavapipe's flushed clip loses";
  for (uint32_t y = 0; y < vk.height; ++y)
    for (uint32_t x = 0; x < vk.width; ++x)
      for (uint32_t s = 0; s < vk.samples; ++s) {
        const size_t i = vk.index(x, y, s);
        if (classes[i] == CoverageClass::Must && vk.owner[i] == kOwnerBackground) {
          EXPECT_LT(y, vk.height / 2) << "missing Must sample (" << x << ", " << y << ") " << s
                                      << " in the bottom draw";
        }
      }
}

TEST(SpecProfileLavapipe, AcceptsLavapipeOnEveryBuiltinScene) {
  const std::string reason = missing_vulkan_reason();
  if (!reason.empty()) GTEST_SKIP() << "no Vulkan device: " << reason;
  VulkanRenderer renderer(VkOptions{.device = "", .validate = true});
  const uint32_t bits = renderer.device().sub_pixel_precision_bits;
  const LavapipeRules rules = test::release_of(renderer).rules();
  Violations total;
  size_t judged = 0, not_supported = 0;
  for (const fs::path& file : builtin_scene_files()) {
    const Scene scene = load_scene_file(file.string());
    try {
      check_spec_profile_support(scene);
    } catch (const NotSupportedError&) {
      ++not_supported;
      continue;
    }
    const RenderResult vk = renderer.render(scene);
    for (const std::string& m : renderer.validation_messages()) ADD_FAILURE() << scene.name << ": validation: " << m;
    const RenderResult spec = render_spec_profile(scene, spec_options(bits), vk);  // vk as the (unused) estimate
    const std::vector<CoverageClass>& classes = spec.coverage_class;
    const Violations v = judge(spec, vk);
    fmt::print("{:52} Must {:8} May {:7} MustNot {:8} | missing {} unexpected {} depth outside {}\n", scene.name,
               v.must, v.may, v.must_not, v.must_missing, v.must_not_covered, v.depth_outside);
    const KnownDeviation* known = known_deviation(scene.name);
    if (known != nullptr && known->gone_with != LavapipeRule::Count && rules.has(known->gone_with)) known = nullptr;
    if (known != nullptr) {
      fmt::print("  known lavapipe deviation: {}\n", known->reason);
      known->check(scene, classes, vk, v);
    } else {
      EXPECT_FALSE(v.any()) << scene.name << ": " << describe(v);
    }
    total.must += v.must;
    total.may += v.may;
    total.must_not += v.must_not;
    total.must_missing += v.must_missing;
    total.must_not_covered += v.must_not_covered;
    total.depth_outside += v.depth_outside;
    ++judged;
  }
  fmt::print(
      "{} scenes judged ({} not supported): Must {}, May {}, MustNot {} samples; {} Must-missing, {} "
      "MustNot-covered, {} depth outside\n",
      judged, not_supported, total.must, total.may, total.must_not, total.must_missing, total.must_not_covered,
      total.depth_outside);
  EXPECT_GT(judged, 40u);
  EXPECT_GT(total.must, 0u);
}

}  // namespace
}  // namespace rastercmp
