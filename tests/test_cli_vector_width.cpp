// lavapipe at 128-bit vectors (LP_NATIVE_VECTOR_WIDTH=128, the width llvmpipe takes on hosts
// without AVX): Mesa keys its on-disk shader cache without the width, so shaders compiled at the
// default 256 bits were loaded at 128 and corrupted lavapipe's heap (vk_reference/vk_shader_cache.hpp).
// A run that sets the width keeps a cache folder of its own, and the scenes that aborted pass.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/test_cli_support.hpp"
#include "vk_reference/vk_shader_cache.hpp"

namespace rastercmp::cli_test {
namespace {

using vk::shader_cache_setting;
using vk::ShaderCacheEnvironment;
using vk::ShaderCacheSetting;
using Action = ShaderCacheSetting::Action;

TEST(ShaderCacheByWidth, TheDefaultWidthKeepsMesasCache) {
  EXPECT_EQ(shader_cache_setting({}).action, Action::Keep);
  EXPECT_EQ(shader_cache_setting({std::string(""), std::nullopt, std::nullopt, std::nullopt, "/home/u"}).action,
            Action::Keep);
}

TEST(ShaderCacheByWidth, ASetWidthGetsAFolderUnderTheRootMesaWouldUse) {
  const ShaderCacheSetting home = shader_cache_setting({"128", std::nullopt, std::nullopt, std::nullopt, "/home/u"});
  EXPECT_EQ(home.action, Action::UseDir);
  EXPECT_EQ(home.dir, "/home/u/.cache/rastercmp-lp-native-vector-width-128");
  const ShaderCacheSetting xdg = shader_cache_setting({"128", std::nullopt, std::nullopt, "/x/", "/home/u"});
  EXPECT_EQ(xdg.dir, "/x/rastercmp-lp-native-vector-width-128");
  const ShaderCacheSetting own = shader_cache_setting({"256", "/c", std::nullopt, "/x", "/home/u"});
  EXPECT_EQ(own.dir, "/c/rastercmp-lp-native-vector-width-256");
}

TEST(ShaderCacheByWidth, AKeyedFolderIsKeptSoAChildDoesNotNestIt) {
  EXPECT_EQ(shader_cache_setting({"128", "/c/rastercmp-lp-native-vector-width-128/", std::nullopt, std::nullopt,
                                  std::nullopt})
                .action,
            Action::Keep);
  // Another width under a keyed folder is keyed again: the folder names one width only.
  EXPECT_EQ(shader_cache_setting({"256", "/c/rastercmp-lp-native-vector-width-128", std::nullopt, std::nullopt,
                                  std::nullopt})
                .dir,
            "/c/rastercmp-lp-native-vector-width-128/rastercmp-lp-native-vector-width-256");
}

TEST(ShaderCacheByWidth, AnOffCacheStaysOffAndNoRootTurnsItOff) {
  EXPECT_EQ(shader_cache_setting({"128", "/c", "true", std::nullopt, "/home/u"}).action, Action::Keep);
  EXPECT_EQ(shader_cache_setting({"128", std::nullopt, std::nullopt, std::nullopt, std::nullopt}).action,
            Action::Disable);
}

TEST(ShaderCacheByWidth, TheValueCannotNameAnotherFolder) {
  EXPECT_EQ(vk::shader_cache_folder_name("../1 28"), "rastercmp-lp-native-vector-width-___1_28");
}

// 22.3.6 aborted here ("malloc(): invalid next size") in about half the runs at 128 bits after a
// run at the default width had filled the same cache, 25.0.7 in about one in ten.
TEST(CliVectorWidth, A128BitRunAfterADefaultRunSharingTheCacheIsExact) {
  RASTERCMP_SKIP_WITHOUT_VULKAN();
  const TempDir tmp;
  const std::string cache = (tmp / "cache").string();
  std::vector<std::string> scenes;
  for (const char* name : {"steep", "clamp_negative", "slope"}) {
    scenes.push_back((kSourceDir / "scenes/depth/bias/d32_sfloat" / (std::string(name) + ".json")).string());
  }
  std::vector<std::string> fill = {"compare"};
  fill.insert(fill.end(), scenes.begin(), scenes.end());
  const RunResult filled = run_cli(fill, {{"MESA_SHADER_CACHE_DIR", cache}});
  ASSERT_EQ(filled.exit_code, 0) << describe(fill, filled);
  // Mesa's cache folder: one file per entry (22.3.6) or the database of parts (the default of
  // Debian 13's and unstable's Mesa)
  ASSERT_TRUE(fs::exists(fs::path(cache) / "mesa_shader_cache") || fs::exists(fs::path(cache) / "mesa_shader_cache_db"))
      << "the default run filled no cache in " << cache;

  for (int run = 0; run < 4; ++run) {
    const RunResult r = run_cli(fill, {{"MESA_SHADER_CACHE_DIR", cache}, {"LP_NATIVE_VECTOR_WIDTH", "128"}});
    const std::string what = describe(fill, r);
    ASSERT_EQ(r.signal, 0) << what;
    EXPECT_EQ(r.exit_code, 0) << what;
    EXPECT_NE(r.out.find("128 bits"), std::string::npos) << "lavapipe did not run at 128 bits\n" << what;
  }
  EXPECT_TRUE(fs::is_directory(fs::path(cache) / "rastercmp-lp-native-vector-width-128"));
}

}  // namespace
}  // namespace rastercmp::cli_test
