// Picking rows out of a CSV read back for charts: equality filters on named columns.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "experiments/csv_log.hpp"

namespace rastercmp::experiments {

using Row = std::vector<std::string>;
using Where = std::vector<std::pair<std::string, std::string>>;

// Rows where every named column holds the given text, in file order.
std::vector<Row> select_rows(const CsvTable& table, const Where& where);

// Distinct values of a column in file order.
std::vector<std::string> distinct(const CsvTable& table, const std::string& column, const Where& where = {});

double to_double(const std::string& text);  // "nan", "inf" understood

}  // namespace rastercmp::experiments
