// Progress of a long sweep on stderr: points done, elapsed time and an estimate of the time left
// (from the points rendered in this run; points skipped by --resume cost nothing).
#pragma once

#include <chrono>
#include <string>

namespace rastercmp::experiments {

class Progress {
 public:
  Progress(std::string label, size_t total);
  void skipped();   // a point already in the CSV
  void finished();  // a point rendered now
  void done();      // final line

 private:
  void print(bool force);
  std::string label_;
  size_t total_, skipped_ = 0, rendered_ = 0;
  std::chrono::steady_clock::time_point start_, last_print_;
};

}  // namespace rastercmp::experiments
