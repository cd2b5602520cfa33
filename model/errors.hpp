// Error kinds and the exit codes they map to (README "Exit codes").
#pragma once

#include <stdexcept>
#include <string>

namespace rastercmp {

enum ExitCode : int {
  kExitOk = 0,
  kExitMismatch = 1,     // differences found (compare, conformance)
  kExitBadInput = 2,     // bad scene file, bad option, unwritable output
  kExitEnvironment = 3,  // no Vulkan loader / ICD / device, missing tool
  kExitInternal = 4,     // a bug or a driver failure we could not classify
};

// Bad input: names the file, the JSON path of the field and what was expected.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string json_path, std::string expected)
      : std::runtime_error(file + ": " + (json_path.empty() ? std::string("$") : json_path) + ": " + expected),
        file_(std::move(file)),
        json_path_(std::move(json_path)),
        expected_(std::move(expected)) {}
  const std::string& file() const { return file_; }
  const std::string& json_path() const { return json_path_; }
  const std::string& expected() const { return expected_; }

 private:
  std::string file_, json_path_, expected_;
};

// Usage errors (bad command-line option values) that are not about a scene file.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The environment cannot run what was asked (no Vulkan, no device, no gnuplot...).
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A feature the chosen backend or profile cannot reproduce (reported as NotSupported).
class NotSupportedError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The driver reported device loss or out-of-memory (reported as ResourceError / InternalError).
class DeviceError : public std::runtime_error {
 public:
  DeviceError(std::string what, bool out_of_memory)
      : std::runtime_error(std::move(what)), out_of_memory_(out_of_memory) {}
  bool out_of_memory() const { return out_of_memory_; }

 private:
  bool out_of_memory_;
};

}  // namespace rastercmp
