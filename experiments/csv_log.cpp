#include "experiments/csv_log.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {
namespace {

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

}  // namespace

size_t CsvTable::column(const std::string& name) const {
  for (size_t c = 0; c < header.size(); ++c)
    if (header[c] == name) return c;
  throw std::out_of_range("CSV has no column " + name);
}

std::string join_fields(const std::vector<std::string>& fields, size_t count) {
  std::string line;
  for (size_t i = 0; i < count && i < fields.size(); ++i) line += (i ? "," : "") + fields[i];
  return line;
}

CsvTable read_csv(const std::string& path) {
  CsvTable table;
  std::ifstream in(path, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  size_t start = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // a row without its newline was cut off mid-write
    std::vector<std::string> fields = split_fields(text.substr(start, end - start));
    start = end + 1;
    if (table.header.empty())
      table.header = std::move(fields);
    else if (fields.size() == table.header.size())
      table.rows.push_back(std::move(fields));
  }
  return table;
}

CsvAppender::CsvAppender(std::string path, std::vector<std::string> header, size_t key_columns, bool resume)
    : path_(std::move(path)), columns_(header.size()), key_columns_(key_columns) {
  std::string kept = join_fields(header, header.size()) + "\n";
  if (resume) {
    const CsvTable old = read_csv(path_);
    if (!old.header.empty() && old.header != header)
      throw InputError(path_, "",
                       "expected a CSV with the header " + join_fields(header, header.size()) +
                           " to resume (delete it or run without --resume)");
    for (const auto& row : old.rows) {
      kept += join_fields(row, row.size()) + "\n";
      keys_.insert(join_fields(row, key_columns_));
    }
  }
  write_text_file_atomic(path_, kept);
  file_ = std::fopen(path_.c_str(), "ab");
  if (!file_) throw InputError(path_, "", "expected a writable file");
}

CsvAppender::~CsvAppender() {
  if (file_) std::fclose(file_);
}

bool CsvAppender::has(const std::vector<std::string>& key) const {
  return keys_.count(join_fields(key, key_columns_)) != 0;
}

void CsvAppender::append(const std::vector<std::string>& row) {
  if (row.size() != columns_) throw std::logic_error("CSV row with the wrong number of fields");
  const std::string line = join_fields(row, row.size()) + "\n";
  if (std::fwrite(line.data(), 1, line.size(), file_) != line.size() || std::fflush(file_) != 0)
    throw InputError(path_, "", "expected a writable file (write failed)");
  keys_.insert(join_fields(row, key_columns_));
}

}  // namespace rastercmp::experiments
