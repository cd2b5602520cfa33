#include "experiments/table_query.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace rastercmp::experiments {

std::vector<Row> select_rows(const CsvTable& table, const Where& where) {
  std::vector<std::pair<size_t, std::string>> tests;
  for (const auto& [column, value] : where) tests.emplace_back(table.column(column), value);
  std::vector<Row> out;
  for (const Row& row : table.rows)
    if (std::all_of(tests.begin(), tests.end(), [&](const auto& t) { return row[t.first] == t.second; }))
      out.push_back(row);
  return out;
}

std::vector<std::string> distinct(const CsvTable& table, const std::string& column, const Where& where) {
  const size_t c = table.column(column);
  std::vector<std::string> out;
  for (const Row& row : select_rows(table, where))
    if (std::find(out.begin(), out.end(), row[c]) == out.end()) out.push_back(row[c]);
  return out;
}

double to_double(const std::string& text) {
  if (text == "nan") return std::nan("");
  if (text == "inf") return INFINITY;
  if (text == "-inf") return -INFINITY;
  return std::strtod(text.c_str(), nullptr);
}

}  // namespace rastercmp::experiments
