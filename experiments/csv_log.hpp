// Append-only CSV for long sweeps: every row is written and flushed as soon as its point is done,
// so an interrupted run loses nothing, and --resume skips the points already in the file.
// Fields never contain commas or quotes (they are numbers and dotted names).
#pragma once

#include <cstdio>
#include <set>
#include <string>
#include <vector>

namespace rastercmp::experiments {

struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // only complete rows (as many fields as the header)

  // Index of a column; throws std::out_of_range when the header lacks it.
  size_t column(const std::string& name) const;
};

// Reads a CSV written by CsvAppender. A missing file gives an empty table.
CsvTable read_csv(const std::string& path);

class CsvAppender {
 public:
  // The first `key_columns` fields of a row identify its point. Without `resume` the file is
  // started afresh; with it, complete rows are kept (a half-written last row is dropped) and
  // their keys are remembered. A file with another header is an InputError.
  CsvAppender(std::string path, std::vector<std::string> header, size_t key_columns, bool resume);
  ~CsvAppender();
  CsvAppender(const CsvAppender&) = delete;
  CsvAppender& operator=(const CsvAppender&) = delete;

  bool has(const std::vector<std::string>& key) const;
  void append(const std::vector<std::string>& row);  // written and flushed at once
  size_t rows_kept() const { return keys_.size(); }

 private:
  std::string path_;
  size_t columns_, key_columns_;
  std::set<std::string> keys_;
  std::FILE* file_ = nullptr;
};

std::string join_fields(const std::vector<std::string>& fields, size_t count);

}  // namespace rastercmp::experiments
