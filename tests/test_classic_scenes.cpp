// Every scene of scenes/methods/ renders through its classic methods and differs from the exact
// path exactly where scenes/methods/expected-failures.txt says the method fails: a listed scene
// differs from the exact path (which reproduces lavapipe), an unlisted one matches it bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cpu_raster/classic/render_classic.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/scene_io.hpp"

namespace rastercmp {
namespace {

namespace fs = std::filesystem;
const fs::path kMethodScenes = fs::path(RASTERCMP_SOURCE_DIR) / "scenes" / "methods";

struct Mismatch {
  size_t owner = 0, depth = 0;
};

Mismatch count_mismatches(const RenderResult& a, const RenderResult& b) {
  Mismatch m;
  for (size_t i = 0; i < a.owner.size(); ++i) {
    m.owner += a.owner[i] != b.owner[i];
    if (a.has_depth()) m.depth += a.depth_raw[i] != b.depth_raw[i];
  }
  return m;
}

// Names listed as `name,Fail` (comments and blank lines skipped).
std::set<std::string> expected_failures() {
  std::ifstream in(kMethodScenes / "expected-failures.txt");
  std::set<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t comma = line.find(',');
    if (comma != std::string::npos && line.substr(comma + 1) == "Fail") names.insert(line.substr(0, comma));
  }
  return names;
}

std::vector<fs::path> method_scene_files() {
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(kMethodScenes))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(ClassicScenes, FailExactlyWhereTheBaselineSays) {
  const std::set<std::string> failures = expected_failures();
  std::set<std::string> seen;
  for (const fs::path& file : method_scene_files()) {
    const Scene scene = load_scene_file(file.string());
    seen.insert(scene.name);
    ASSERT_FALSE(scene.methods.empty()) << scene.name << " selects a method";
    CpuOptions exact_options;
    exact_options.fma = true;
    CpuOptions classic_options = exact_options;
    classic_options.methods = scene.methods;
    const RenderResult exact = render_cpu(scene, exact_options);
    const RenderResult classic = render_classic(scene, classic_options);
    const Mismatch m = count_mismatches(classic, exact);
    std::printf("%-62s owner %4zu depth %4zu\n", scene.name.c_str(), m.owner, m.depth);
    const bool differs = m.owner + m.depth > 0;
    EXPECT_EQ(differs, failures.count(scene.name) == 1) << scene.name;
  }
  for (const std::string& name : failures) EXPECT_EQ(seen.count(name), 1u) << name << " is listed but has no scene";
}

}  // namespace
}  // namespace rastercmp
