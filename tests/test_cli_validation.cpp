// The Khronos validation layer over the built `rastercmp` executable: `render --backend vulkan
// --validate` on scenes that use every depth format, MSAA, lines, bias and several draws must
// report nothing (app/cmd_render.cpp prints each message as "validation: ..." and exits 4).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"

namespace rastercmp::cli_test {
namespace {

const std::vector<std::string> kScenes = {
    "depth/format/d16_unorm.json",
    "depth/format/x8_d24_unorm.json",
    "depth/format/none.json",
    "depth/bias/d32_sfloat/slope.json",
    "msaa/depth/intersecting.json",
    "msaa/lines/mixed_modes.json",
    "clip/all_planes.json",
    "multidraw/mixed_state.json",
    "topology/indexed/triangle_fan.json",
};

TEST(CliValidation, VulkanRenderUnderTheValidationLayerIsClean) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  for (const std::string& scene : kScenes) {
    const std::vector<std::string> args = {"render",
                                           (kSourceDir / "scenes" / scene).string(),
                                           "--backend",
                                           "vulkan",
                                           "--validate",
                                           "--out",
                                           (tmp / scene).string()};
    const RunResult r = run_cli(args);
    const std::string what = describe(args, r);
    EXPECT_EQ(r.exit_code, 0) << what;
    EXPECT_EQ(r.err.find("validation"), std::string::npos) << what;
    EXPECT_TRUE(fs::is_regular_file(tmp / scene / "owner.tif")) << what;
  }
}

}  // namespace
}  // namespace rastercmp::cli_test
