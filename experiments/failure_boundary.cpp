#include "experiments/failure_boundary.hpp"

#include <stdexcept>

#include "experiments/method_maps.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {

double map_measure(const CsvTable& table, const std::vector<std::string>& row, const std::string& measure) {
  if (measure == "any_mismatch")
    return to_double(row[table.column("coverage_mismatch")]) + to_double(row[table.column("depth_mismatch")]);
  return to_double(row[table.column(measure)]);
}

std::vector<FailureBoundary> failure_boundaries(const CsvTable& table) {
  std::vector<FailureBoundary> out;
  const size_t param = table.column("param_a"), agree = table.column("cpu_vk_agree");
  for (const MapExperiment& e : method_map_experiments()) {
    const std::string experiment(e.name);
    const std::string measure(e.measure);
    for (const std::string& case_name : distinct(table, "case", {{"experiment", experiment}}))
      for (const std::string& method : distinct(table, "method", {{"experiment", experiment}, {"case", case_name}})) {
        FailureBoundary b{experiment, std::string(e.family), case_name, method};
        double previous = NAN;
        for (const Row& row :
             select_rows(table, {{"experiment", experiment}, {"case", case_name}, {"method", method}})) {
          ++b.points;
          if (row[agree] == "not_supported") {
            ++b.refused;
            continue;
          }
          const double p = to_double(row[param]);
          if (map_measure(table, row, measure) > 0) {
            ++b.failing;
            if (std::isnan(b.boundary)) {
              b.boundary = p;
              b.last_clean = previous;
            }
          }
          previous = p;
        }
        out.push_back(b);
      }
  }
  return out;
}

const FailureBoundary& find_boundary(const std::vector<FailureBoundary>& all, const std::string& experiment,
                                     const std::string& case_name, const std::string& method) {
  for (const FailureBoundary& b : all)
    if (b.experiment == experiment && b.case_name == case_name && b.method == method) return b;
  throw std::out_of_range("no series " + experiment + " / " + case_name + " / " + method);
}

}  // namespace rastercmp::experiments
