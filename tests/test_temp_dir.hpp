// A test's own scratch folder under the system's temporary directory, emptied before use and
// left for inspection after a failure (the next run empties it again).
#pragma once

#include <filesystem>
#include <string>

namespace rastercmp::test_support {

// temp_directory_path() / ("rastercmp_test_" + name), created empty.
inline std::filesystem::path fresh_temp_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("rastercmp_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace rastercmp::test_support
