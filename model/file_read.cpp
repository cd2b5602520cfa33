#include "model/file_read.hpp"

#include <fmt/core.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "model/errors.hpp"

namespace rastercmp {
namespace {

std::string size_text(uint64_t bytes) {
  if (bytes >= (uint64_t(1) << 20) && bytes % (uint64_t(1) << 20) == 0) return fmt::format("{} MiB", bytes >> 20);
  return fmt::format("{} bytes", bytes);
}

}  // namespace

std::string read_at_most(std::istream& in, uint64_t max_bytes) {
  std::string text;
  constexpr size_t kChunk = size_t(1) << 20;
  while (in && text.size() <= max_bytes) {
    const size_t old_size = text.size();
    text.resize(old_size + kChunk);
    in.read(text.data() + old_size, std::streamsize(kChunk));
    text.resize(old_size + size_t(in.gcount()));
  }
  return text;
}

void check_bounded_file(const std::string& path, uint64_t max_bytes, const std::string& what) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(path, "", "expected " + what + ", found no such file");
  if (!fs::is_regular_file(status))
    throw InputError(path, "", "expected " + what + " as a regular file, not a folder, pipe or device");
  const uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, "", "expected " + what + " whose size can be read: " + ec.message());
  if (size > max_bytes)
    throw InputError(path, "",
                     fmt::format("expected {} of at most {}, found {} bytes", what, size_text(max_bytes), size));
}

std::string read_bounded_file(const std::string& path, uint64_t max_bytes, const std::string& what) {
  check_bounded_file(path, max_bytes, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "", fmt::format("expected {} that can be read: {}", what, std::strerror(errno)));
  std::string text = read_at_most(in, max_bytes);
  if (in.bad()) throw InputError(path, "", fmt::format("expected {} that can be read: {}", what, std::strerror(errno)));
  if (text.size() > max_bytes)
    throw InputError(path, "",
                     fmt::format("expected {} of at most {}, found more (it grew)", what, size_text(max_bytes)));
  return text;
}

}  // namespace rastercmp
