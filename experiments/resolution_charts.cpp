// The outputs of `rastercmp chart resolution`: resolution.csv, resolution.json, one log-log chart per
// group of families (mismatch fraction against size, with each method's predicted line) and index.html.
#include <cmath>
#include <filesystem>
#include <map>

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "experiments/doc_table_renderers.hpp"
#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/resolution_sweep.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {
namespace {

struct MethodFit {
  const ResolutionMethod* method = nullptr;
  std::vector<ResolutionPoint> points;  // by size
  double exponent = NAN;                // measured, of the count
  double anchor = NAN;                  // log2 of the predicted fraction at size 1 (least squares, slope fixed)
  bool refused = false, any = false;
  bool agrees() const { return std::isfinite(exponent) && std::fabs(exponent - method->predicted_exponent) <= kExponentTolerance; }
  double predicted_fraction(uint32_t size) const {
    return std::exp2(anchor + (method->predicted_exponent - 2) * std::log2(double(size)));
  }
};

std::vector<MethodFit> fit(const std::vector<ResolutionMethod>& methods, const std::vector<ResolutionPoint>& points,
                           size_t sizes) {
  std::vector<MethodFit> fits;
  for (size_t k = 0; k < methods.size(); ++k) {
    MethodFit f;
    f.method = &methods[k];
    f.points.assign(points.begin() + long(k * sizes), points.begin() + long((k + 1) * sizes));
    f.exponent = count_exponent(f.points);
    double sum = 0, n = 0;
    for (const ResolutionPoint& p : f.points) {
      f.refused = f.refused || p.refused;
      if (p.refused || p.either == 0) continue;
      f.any = true;
      sum += std::log2(p.fraction()) - (f.method->predicted_exponent - 2) * std::log2(double(p.size));
      n += 1;
    }
    f.anchor = n > 0 ? sum / n : NAN;
    fits.push_back(f);
  }
  return fits;
}

// The charts: the families in groups of a readable size.
struct Group {
  std::string name, title;
  std::vector<std::string> families;
};
const std::vector<Group>& groups() {
  static const std::vector<Group> g = {
      {"resolution_fill", "fill and set-up (predicted: fraction ~ 1/size)", {"fill", "set-up"}},
      {"resolution_depth", "depth interpolation (predicted: fraction constant)", {"depth interpolation"}},
      {"resolution_surfaces", "clipping, visibility, culling (predicted: fraction constant)",
       {"clipping", "visibility", "culling"}},
      {"resolution_lines", "lines and line clipping (predicted: fraction ~ 1/size)", {"line", "line clipping"}}};
  return g;
}

// Returns whether a chart was drawn (false: no method of the group differs at any size).
bool chart_group(const std::string& dir, const Group& group, const std::vector<MethodFit>& fits,
                 const std::vector<uint32_t>& sizes) {
  std::vector<DataBlock> blocks;
  std::string plot;
  for (const MethodFit& f : fits) {
    bool in = false;
    for (const std::string& family : group.families) in = in || f.method->family == family;
    if (!in || !f.any) continue;
    DataBlock block{f.method->method, {}};
    for (const ResolutionPoint& p : f.points)
      block.rows.push_back({std::to_string(p.size), p.refused || p.either == 0 ? "NaN" : num(p.fraction()),
                            num(f.predicted_fraction(p.size))});
    const size_t i = blocks.size();
    plot += fmt::format("{}DATA index {} using 1:2 with points lt {} title {}, "
                        "DATA index {} using 1:3 with lines lt {} notitle",
                        i ? ", \\\n  " : "", i, i + 1,
                        gp_quote(fmt::format("{} (exponent {:.2f}, predicted {})", f.method->method, f.exponent,
                                             f.method->predicted_exponent)),
                        i, i + 1);
    blocks.push_back(block);
  }
  if (blocks.empty()) return false;
  plot += ", \\\n  NaN with lines lc rgb '#444444' title 'lines: the predicted slope, fitted through the points'";
  render_chart(dir, group.name, blocks,
               "set title " + gp_quote("Mismatch against the exact path by framebuffer size: " + group.title) +
                   "\nset logscale xy 2\nset logscale y 10\nset format y '10^{%L}'\n"
                   "set xtics (" + fmt::format("{}", fmt::join(sizes, ", ")) + ")\nset xrange [" +
                   num(sizes.front() * 0.75) + ":" + num(sizes.back() * 1.33) + "]\nset grid\n"
                   "set xlabel 'framebuffer width = height (px)'\n"
                   "set ylabel 'samples that differ (owner or raw depth) / samples'\n"
                   "set key outside below font ',10' maxrows 4\n"
                   "plot " + plot + "\n");
  return true;
}

std::string json_text(const std::vector<MethodFit>& fits, const std::vector<uint32_t>& sizes) {
  nlohmann::ordered_json out;
  out["sizes"] = sizes;
  out["reference"] = "exact path (scalar), same options";
  out["fma"] = exact_cpu_options().fma;
  out["exponent_tolerance"] = kExponentTolerance;
  out["methods"] = nlohmann::ordered_json::array();
  for (const MethodFit& f : fits) {
    nlohmann::ordered_json m{{"family", f.method->family},
                             {"method", f.method->method},
                             {"set", f.method->lines ? "lines" : "triangles"},
                             {"predicted_exponent", f.method->predicted_exponent},
                             {"measured_exponent", std::isfinite(f.exponent) ? nlohmann::ordered_json(f.exponent)
                                                                             : nlohmann::ordered_json()},
                             {"agrees", std::isfinite(f.exponent) ? nlohmann::ordered_json(f.agrees())
                                                                  : nlohmann::ordered_json()},
                             {"refused", f.refused}};
    m["points"] = nlohmann::ordered_json::array();
    for (const ResolutionPoint& p : f.points)
      m["points"].push_back({{"size", p.size},
                             {"samples", p.samples},
                             {"coverage", p.coverage},
                             {"depth", p.depth},
                             {"either", p.either},
                             {"fraction", p.fraction()},
                             {"predicted_fraction", f.any ? nlohmann::ordered_json(f.predicted_fraction(p.size))
                                                          : nlohmann::ordered_json()}});
    out["methods"].push_back(m);
  }
  return out.dump(2) + "\n";
}

}  // namespace

void run_resolution_sweep(const SweepOptions& options) {
  find_gnuplot();
  prepare_out_dir(options.out_dir);
  const std::vector<uint32_t> sizes = resolution_sizes(options.quick);
  const std::vector<ResolutionMethod> methods = resolution_methods();
  const std::vector<ResolutionPoint> points = measure_resolution(methods, sizes);
  const std::vector<MethodFit> fits = fit(methods, points, sizes.size());
  std::string csv = "family,method,size,samples,coverage,depth,either,fraction,refused\n";
  for (const ResolutionPoint& p : points)
    csv += fmt::format("{},{},{},{},{},{},{},{},{}\n", p.family, p.method, p.size, p.samples, p.coverage, p.depth,
                       p.either, num(p.fraction()), flag(p.refused));
  write_text_file_atomic((std::filesystem::path(options.out_dir) / "resolution.csv").string(), csv);
  const std::string json = json_text(fits, sizes);
  write_json_file(options.out_dir, "resolution.json", json);
  write_resolution_tables(options.out_dir, json);

  std::vector<PageSection> sections{
      {"Method",
       "The speed-accuracy scene sets (triangles: coplanar pair, house, sliver pair, mesh; lines: a star and lines "
       "crossing the frame) rendered at each square size, each method against the exact path, sample by sample "
       "(owner or raw depth). Rule: an error of fixed sub-pixel width along edges or lines differs on ~size samples "
       "(fraction ~ 1/size, exponent 1); an error inside every covered pixel on ~size^2 (fraction constant, exponent "
       "2). The exponent is the least-squares slope of log count on log size over the sizes with a non-zero count; "
       "the rule holds when it lies within " + fmt::format("{}", kExponentTolerance) +
           " of the prediction. Lines: the prediction with the slope fixed, fitted through the points.",
       {}}};
  for (const Group& g : groups()) {
    std::vector<std::vector<std::string>> table{{"method", "predicted exponent", "measured exponent", "rule holds"}};
    for (uint32_t size : sizes) table[0].push_back(fmt::format("differ at {}", size));
    for (const MethodFit& f : fits) {
      bool in = false;
      for (const std::string& family : g.families) in = in || f.method->family == family;
      if (!in) continue;
      std::vector<std::string> row{f.method->method, std::to_string(f.method->predicted_exponent),
                                   std::isfinite(f.exponent) ? fmt::format("{:.2f}", f.exponent) : "—",
                                   !f.any                       ? "no mismatch"
                                   : !std::isfinite(f.exponent) ? "differs at one size only"
                                   : f.agrees()                 ? "yes"
                                                                : "no"};
      for (const ResolutionPoint& p : f.points) row.push_back(p.refused ? "refused" : std::to_string(p.either));
      table.push_back(row);
    }
    const bool drawn = chart_group(options.out_dir, g, fits, sizes);
    sections.push_back({g.title, drawn ? "" : "No method of this group differs from the exact path at any size.",
                        drawn ? std::vector<std::string>{g.name} : std::vector<std::string>{}, table});
  }
  write_index_html(options.out_dir, "Mismatch against framebuffer size", sections, {"resolution.csv", "resolution.json"});
}

}  // namespace rastercmp::experiments
