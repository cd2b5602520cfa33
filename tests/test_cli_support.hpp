// Helpers for the tests that run the built `rastercmp` executable (tests/test_cli_*.cpp):
// spawn it with captured stdout / stderr and an edited environment, temporary folders, and
// snapshots of a folder tree to prove that a failed command left it as it was.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

extern char** environ;

namespace rastercmp::cli_test {

namespace fs = std::filesystem;

inline const fs::path kSourceDir = RASTERCMP_SOURCE_DIR;
inline const fs::path kBinary = fs::path(RASTERCMP_BINARY_DIR) / "app" / "rastercmp";

// Environment edits for one run: NAME=VALUE pairs set (or replaced) in the child's environment.
using EnvEdits = std::vector<std::pair<std::string, std::string>>;

// Pointing the Vulkan loader at a driver manifest that does not exist hides every device.
inline const EnvEdits kNoVulkanDriver = {{"VK_ICD_FILENAMES", "/nonexistent/rastercmp_no_icd.json"},
                                         {"VK_DRIVER_FILES", "/nonexistent/rastercmp_no_icd.json"}};

// Naming a loader library that does not exist (RASTERCMP_VULKAN_LOADER, vk_reference/vk_loader.hpp)
// is a machine without the Vulkan loader: libvulkan.so.1 is opened at run time, never linked.
inline const EnvEdits kNoVulkanLoader = {{"RASTERCMP_VULKAN_LOADER", "/nonexistent/libvulkan.so.1"}};

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_file(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// A fresh folder under the system temporary folder, removed (with everything in it) at scope end.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "rastercmp_cli_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

// Holds the --out lock of `dir` (created if need be) as a running rastercmp would, its lock file
// naming pid 31337, until release() or the end of the object.
class HeldOutputLock {
 public:
  explicit HeldOutputLock(const fs::path& dir) {
    fs::create_directories(dir);
    fd_ = open((dir / ".rastercmp.lock").c_str(), O_RDWR | O_CREAT, 0644);
    const std::string pid = "31337\n";
    if (fd_ < 0 || flock(fd_, LOCK_EX | LOCK_NB) != 0 || write(fd_, pid.data(), pid.size()) != ssize_t(pid.size()))
      throw std::runtime_error("could not hold the lock of " + dir.string());
  }
  ~HeldOutputLock() { release(); }
  HeldOutputLock(const HeldOutputLock&) = delete;
  HeldOutputLock& operator=(const HeldOutputLock&) = delete;
  void release() {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
  }

 private:
  int fd_ = -1;
};

// How a finished child ended: exit code, or the signal that killed it.
struct RunResult {
  int exit_code = -1;  // -1 when killed by a signal
  int signal = 0;      // 0 when it exited
  std::string out;
  std::string err;
};

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Printed by a failing EXPECT: how the command was run and what it said.
inline std::string describe(const std::vector<std::string>& args, const RunResult& r) {
  std::string text = "rastercmp";
  for (const std::string& a : args) text += " " + a;
  text += "\n  exit " + std::to_string(r.exit_code) + ", signal " + std::to_string(r.signal);
  text += "\n  stdout: " + r.out + "\n  stderr: " + r.err;
  return text;
}

// The built executable running in the background, stdout / stderr going to files.
class Child {
 public:
  Child(const std::vector<std::string>& args, const EnvEdits& env = {}) {
    std::string pattern = (fs::temp_directory_path() / "rastercmp_cli_io_XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    io_dir_ = pattern;
    std::vector<std::string> argv_text{kBinary.string()};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<std::string> env_text = edited_environment(env);
    std::vector<char*> argv = pointers(argv_text), envp = pointers(env_text);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    const std::string out_path = (io_dir_ / "stdout").string(), err_path = (io_dir_ / "stderr").string();
    posix_spawn_file_actions_addopen(&actions, 1, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int spawned = posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0) throw std::runtime_error("posix_spawn " + kBinary.string() + ": " + std::strerror(spawned));
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    std::error_code ec;
    fs::remove_all(io_dir_, ec);
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  void send_signal(int signal) const { kill(pid_, signal); }

  RunResult wait() {
    int status = 0;
    while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    RunResult r;
    if (WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) r.signal = WTERMSIG(status);
    r.out = read_file(io_dir_ / "stdout");
    r.err = read_file(io_dir_ / "stderr");
    return r;
  }

 private:
  static std::vector<std::string> edited_environment(const EnvEdits& edits) {
    std::vector<std::string> env;
    for (char** e = environ; *e != nullptr; ++e) {
      const std::string entry = *e;
      bool replaced = false;
      for (const auto& [name, value] : edits) replaced = replaced || entry.rfind(name + "=", 0) == 0;
      if (!replaced) env.push_back(entry);
    }
    for (const auto& [name, value] : edits) env.push_back(name + "=" + value);
    return env;
  }
  static std::vector<char*> pointers(std::vector<std::string>& texts) {
    std::vector<char*> p;
    for (std::string& t : texts) p.push_back(t.data());
    p.push_back(nullptr);
    return p;
  }

  pid_t pid_ = 0;
  fs::path io_dir_;
};

inline RunResult run_cli(const std::vector<std::string>& args, const EnvEdits& env = {}) {
  Child child(args, env);
  return child.wait();
}

// Every entry below `root` (relative path → file bytes, or "<dir>"), to compare before and after.
using TreeSnapshot = std::map<std::string, std::string>;

inline TreeSnapshot snapshot_tree(const fs::path& root) {
  TreeSnapshot tree;
  std::error_code ec;
  if (!fs::exists(root, ec)) return tree;
  if (!fs::is_directory(root, ec)) {
    tree[""] = read_file(root);
    return tree;
  }
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(root)) {
    const std::string rel = fs::relative(e.path(), root).string();
    tree[rel] = e.is_directory() ? std::string("<dir>") : read_file(e.path());
  }
  return tree;
}

// The regular files of a snapshot (folders dropped).
inline TreeSnapshot files_of(const TreeSnapshot& tree) {
  TreeSnapshot files;
  for (const auto& [path, content] : tree)
    if (content != "<dir>") files[path] = content;
  return files;
}

// summary.json's cases by scene name.
inline std::map<std::string, nlohmann::json> cases_by_name(const nlohmann::json& summary) {
  std::map<std::string, nlohmann::json> cases;
  for (const nlohmann::json& c : summary.at("cases")) cases[c.at("scene").get<std::string>()] = c;
  return cases;
}

// Whether process `pid` has ended (gone, or a zombie nobody reaps: a container's init may not).
inline bool process_ended(pid_t pid) {
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  if (!std::getline(stat, text)) return true;
  const auto paren = text.rfind(')');
  return paren != std::string::npos && paren + 2 < text.size() && text[paren + 2] == 'Z';
}

// Whether process `pid` ends within 10 s (a SIGKILL is delivered at once; the time allows a busy
// machine). One that does not is killed, so no test leaves it behind.
inline bool process_ends_soon(pid_t pid) {
  for (int k = 0; k < 100; ++k) {
    if (process_ended(pid)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  kill(pid, SIGKILL);
  return false;
}

// Skips the current test when `rastercmp devices` finds no Vulkan device (exit 3, the
// documented "no loader / ICD / device" code); any other failure of `devices` fails the test.
#define RASTERCMP_SKIP_WITHOUT_VULKAN()                                                            \
  do {                                                                                             \
    const ::rastercmp::cli_test::RunResult devices_ = ::rastercmp::cli_test::run_cli({"devices"}); \
    if (devices_.exit_code == 3) GTEST_SKIP() << "no Vulkan device: " << devices_.err;             \
    ASSERT_EQ(devices_.exit_code, 0) << ::rastercmp::cli_test::describe({"devices"}, devices_);    \
  } while (false)

}  // namespace rastercmp::cli_test
