#include "experiments/progress.hpp"

#include <fmt/core.h>

namespace rastercmp::experiments {

Progress::Progress(std::string label, size_t total)
    : label_(std::move(label)), total_(total), start_(std::chrono::steady_clock::now()), last_print_(start_) {}

void Progress::skipped() { ++skipped_; }

void Progress::finished() {
  ++rendered_;
  print(false);
}

void Progress::done() { print(true); }

void Progress::print(bool force) {
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_print_ < std::chrono::milliseconds(500)) return;
  last_print_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const size_t done_count = skipped_ + rendered_;
  const size_t left = total_ > done_count ? total_ - done_count : 0;
  const double per_point = rendered_ ? elapsed / double(rendered_) : 0.0;
  fmt::print(stderr, "[{}] {}/{} points ({} resumed), {:.1f} s elapsed, about {:.0f} s left\n", label_, done_count,
             total_, skipped_, elapsed, per_point * double(left));
}

}  // namespace rastercmp::experiments
