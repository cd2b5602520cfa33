// Replays every fuzz seed and every input a fuzzer ever crashed on (fuzz/regressions/) through
// the fuzz targets' checks: a crash found once stays fixed.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fuzz/fuzz_checks.hpp"

namespace fs = std::filesystem;

namespace {

std::vector<fs::path> inputs_in(const std::string& relative) {
  std::vector<fs::path> files;
  const fs::path dir = fs::path(RASTERCMP_SOURCE_DIR) / relative;
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir))
      if (entry.is_regular_file()) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

template <typename Check>
size_t replay(const std::vector<std::string>& dirs, Check check) {
  size_t count = 0;
  for (const std::string& dir : dirs)
    for (const fs::path& file : inputs_in(dir)) {
      SCOPED_TRACE(file.string());
      const std::vector<uint8_t> bytes = read_bytes(file);
      check(bytes.data(), bytes.size());
      ++count;
    }
  return count;
}

}  // namespace

TEST(FuzzRegressions, SceneParserInputsParseOrFailCleanly) {
  const size_t n =
      replay({"fuzz/corpus/scene_parser", "fuzz/regressions/scene_parser"}, rastercmp::fuzz::check_scene_parser);
  EXPECT_GT(n, 0u) << "the scene-parser seed corpus is empty";
}

TEST(FuzzRegressions, ClipperInputsKeepTheirProperties) {
  const size_t n = replay({"fuzz/corpus/clipper", "fuzz/regressions/clipper"}, rastercmp::fuzz::check_clipper);
  EXPECT_GT(n, 0u) << "the clipper seed corpus is empty";
}
