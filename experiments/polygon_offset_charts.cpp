// Charts and page of `sweep polygon-offset`, from polygon_offset.csv read back (so a resumed run
// charts every point) and from the r measurements.
#include <cmath>
#include <filesystem>

#include <fmt/core.h>

#include "experiments/gnuplot.hpp"
#include "experiments/html_page.hpp"
#include "experiments/polygon_offset.hpp"
#include "experiments/table_query.hpp"

namespace rastercmp::experiments {
namespace {

const char* kLogX = "set logscale x 10\nset format x '10^{%L}'\n";
const char* kStyle = "set key outside right top\nset grid\nset yrange [-0.02:1.02]\nset style data linespoints\n";

std::string offset_label(const std::string& constant, const std::string& slope) {
  return constant == "0" && slope == "0" ? "no offset" : "constant " + constant + ", slope " + slope;
}

// One line per (format, offset) of the far_near experiment of a scene.
void chart_far_near(const std::string& dir, const CsvTable& table, const std::string& scene) {
  std::vector<DataBlock> blocks;
  const Where base{{"experiment", "far_near"}, {"scene", scene}};
  const size_t ratio = table.column("far_near"), wrong = table.column("wrong_cpu"), wrong_vk = table.column("wrong_vk");
  for (const std::string& format : distinct(table, "format", base))
    for (const std::string& constant : distinct(table, "constant", base)) {
      Where where = base;
      where.push_back({"format", format});
      where.push_back({"constant", constant});
      const std::vector<Row> rows = select_rows(table, where);
      if (rows.empty()) continue;
      DataBlock block{format + ", " + offset_label(constant, rows.front()[table.column("slope")]), {}};
      for (const Row& row : rows) block.rows.push_back({row[ratio], row[wrong], row[wrong_vk]});
      blocks.push_back(block);
    }
  std::string body = std::string(kLogX) + kStyle +
                     fmt::format(
                         "set title 'Z-fighting of the {} decal against far/near (CPU lines, Vulkan crosses)'\n"
                         "set xlabel 'far / near'\nset ylabel 'fraction of decal pixels won by the wrong surface'\n",
                         scene);
  body += "plot for [i=0:" + std::to_string(blocks.size() - 1) +
          "] DATA index i using 1:2 title columnheader(1) lt (i+1), \\\n"
          "     for [i=0:" +
          std::to_string(blocks.size() - 1) + "] DATA index i using 1:3 notitle with points pt 2 ps 1.4 lc (i+1)\n";
  for (DataBlock& block : blocks) block.rows.insert(block.rows.begin(), {"\"" + block.title + "\"", "x", "x"});
  render_chart(dir, "zfight_far_near_" + scene, blocks, body);
}

// Smallest factor (constant or slope) with no wrong pixel on either backend, per angle.
void chart_min_offset(const std::string& dir, const CsvTable& table, const std::string& axis) {
  std::vector<DataBlock> blocks;
  const size_t value = table.column(axis);
  const size_t wrong = table.column("wrong_cpu"), wrong_vk = table.column("wrong_vk");
  const Where base{{"experiment", axis}};
  for (const std::string& scene : distinct(table, "scene", base))
    for (const std::string& format : distinct(table, "format", base)) {
      DataBlock block{scene + ", " + format, {{"\"" + scene + ", " + format + "\"", "x"}}};
      for (const std::string& a : distinct(table, "angle_deg", base)) {
        double smallest = NAN;
        for (const Row& row :
             select_rows(table, {{"experiment", axis}, {"scene", scene}, {"format", format}, {"angle_deg", a}}))
          if (to_double(row[wrong]) == 0 && to_double(row[wrong_vk]) == 0 && !(to_double(row[value]) >= smallest))
            smallest = to_double(row[value]);
        // 0 is drawn at 1/8 on the log axis (tic "0").
        block.rows.push_back({a, std::isnan(smallest) ? "NaN" : fmt::format("{}", smallest == 0 ? 0.125 : smallest)});
      }
      blocks.push_back(block);
    }
  const std::string body = fmt::format(
      "set title 'Smallest {} factor that removes z-fighting, against viewing angle (depth slope)'\n"
      "set xlabel 'angle between the plane and the image plane (degrees); depth slope grows as tan(angle)'\n"
      "set ylabel 'smallest {} factor with no wrong pixel'\nset logscale y 2\nset ytics add ('0' 0.125)\n"
      "set key outside right top\nset grid\nset style data linespoints\n"
      "plot for [i=0:{}] DATA index i using 1:2 title columnheader(1) lt (i+1)\n",
      axis, axis, blocks.size() - 1);
  render_chart(dir, "min_" + axis + "_vs_angle", blocks, body);
}

void chart_clamp(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const size_t clamp = table.column("clamp"), wrong = table.column("wrong_cpu");
  for (const std::string& format : distinct(table, "format", {{"experiment", "clamp"}})) {
    DataBlock block{format, {{format, "x"}}};
    for (const Row& row : select_rows(table, {{"experiment", "clamp"}, {"format", format}})) {
      const double c = to_double(row[clamp]);
      block.rows.push_back({c == 0 ? "1" : fmt::format("{}", -c), row[wrong]});  // no clamp drawn at 1
    }
    blocks.push_back(block);
  }
  const std::string body = std::string(kLogX) + kStyle +
                           "set title 'Depth-bias clamp: a decal with constant 256, slope 4 at 60 degrees'\n"
                           "set xlabel '|clamp| (the point at 1 = clamp 0, no clamp)'\n"
                           "set ylabel 'fraction won by the wrong surface'\nset xtics add ('off' 1)\n"
                           "plot for [i=0:" +
                           std::to_string(blocks.size() - 1) +
                           "] DATA index i using 1:2 title columnheader(1) lt (i+1)\n";
  render_chart(dir, "clamp", blocks, body);
}

void chart_angle(const std::string& dir, const CsvTable& table) {
  std::vector<DataBlock> blocks;
  const size_t angle = table.column("angle_deg"), wrong = table.column("wrong_cpu");
  const Where base{{"experiment", "angle"}};
  for (const std::string& scene : distinct(table, "scene", base))
    for (const std::string& format : distinct(table, "format", base))
      for (const std::string& constant : distinct(table, "constant", base)) {
        const std::vector<Row> rows =
            select_rows(table, {{"experiment", "angle"}, {"scene", scene}, {"format", format}, {"constant", constant}});
        const std::string title =
            scene + ", " + format + ", " + offset_label(constant, rows.front()[table.column("slope")]);
        DataBlock block{title, {{"\"" + title + "\"", "x"}}};
        for (const Row& row : rows) block.rows.push_back({row[angle], row[wrong]});
        blocks.push_back(block);
      }
  const std::string body = std::string(kStyle) +
                           "set title 'Wrong surface against viewing angle (far/near 1000)'\n"
                           "set xlabel 'angle (degrees)'\nset ylabel 'fraction won by the wrong surface'\n"
                           "plot for [i=0:" +
                           std::to_string(blocks.size() - 1) +
                           "] DATA index i using 1:2 title columnheader(1) lt (i+1)\n";
  render_chart(dir, "wrong_vs_angle", blocks, body);
}

// r / spec bound per format: the measured ratio on each backend beside lavapipe's predicted one
// (depth_r_blocks), on a linear axis, where D16's excess 2^16/(2^16-1) = 1.0000153 shows.
void chart_r(const std::string& dir, const std::vector<DepthRMeasure>& measures) {
  std::vector<DataBlock> blocks = depth_r_blocks(measures);
  std::string tics;
  for (size_t i = 0; i < measures.size(); ++i)
    tics += fmt::format("{}{} {}", i ? ", " : "",
                        gp_quote(std::string(to_string(measures[i].format)) +
                                 (measures[i].format == DepthFormat::D32Sfloat ? " at z 0.375" : "")),
                        i);
  const std::string body = fmt::format(
      "set title 'r (depth step of constantFactor 1) per format, divided by the spec bound'\n"
      "set ylabel 'r / spec bound (UNORM: 2 x 2^-n; D32: 2^(e-23))'\nset format y '%.7f'\n"
      "set xrange [-0.6:{}-0.4]\nset xtics noenhanced ({})\nset key outside right top\nset grid\n"
      "set arrow from graph 0, first 1 to graph 1, first 1 nohead dt 2 lc rgb '#888888'\n"
      "plot DATA index 2 using 1:3:(0.3) title columnheader(2) with xerrorbars lc rgb '#2ca02c' lw 2 pt 0, \\\n"
      "     DATA index 0 using 1:3 title columnheader(2) with points lt 1 pt 7 ps 2.5, \\\n"
      "     DATA index 1 using 1:3 title columnheader(2) with points lt 2 pt 2 ps 3\n",
      measures.size(), tics);
  for (DataBlock& block : blocks) block.rows.insert(block.rows.begin(), {"x", "\"" + block.title + "\"", "x"});
  render_chart(dir, "depth_r", blocks, body);
}

}  // namespace

std::vector<DataBlock> depth_r_blocks(const std::vector<DepthRMeasure>& measures) {
  std::vector<DataBlock> blocks{{"measured r / bound, CPU", {}},
                                {"measured r / bound, Vulkan", {}},
                                {"predicted (lavapipe: 2/(2^n-1) UNORM, 2^(e-23) D32) / bound", {}}};
  for (size_t i = 0; i < measures.size(); ++i) {
    const DepthRMeasure& m = measures[i];
    const std::string x = std::to_string(i), name = to_string(m.format);
    blocks[0].rows.push_back({x, name, fmt::format("{:.10g}", m.r_cpu / m.spec_bound)});
    blocks[1].rows.push_back({x, name, fmt::format("{:.10g}", m.r_vk / m.spec_bound)});
    blocks[2].rows.push_back({x, name, fmt::format("{:.10g}", m.lavapipe_formula / m.spec_bound)});
  }
  return blocks;
}

void write_polygon_offset_charts(const std::string& dir, const std::vector<DepthRMeasure>& r) {
  const CsvTable table = read_csv((std::filesystem::path(dir) / kPolygonOffsetCsv).string());
  std::vector<std::string> far_near_charts;
  for (const std::string& scene : distinct(table, "scene", {{"experiment", "far_near"}})) {
    chart_far_near(dir, table, scene);
    far_near_charts.push_back("zfight_far_near_" + scene);
  }
  chart_min_offset(dir, table, "constant");
  chart_min_offset(dir, table, "slope");
  chart_clamp(dir, table);
  chart_angle(dir, table);
  chart_r(dir, r);
  PageSection control{"Control: one triangle drawn twice",
                      "The same triangle (same vertices) drawn twice under compare op Less, the second with constant "
                      "offset 0 and 1 (units of r) towards the eye, on every depth format and at several viewing "
                      "angles (polygon_offset.json). Without offset the two depths are equal and the second draw loses "
                      "every pixel; the spec makes r the smallest difference that separates two depths, so with 1 r "
                      "it must win every pixel.",
                      {},
                      {{"format", "angle (degrees)", "constant (r)", "lost by the second draw, CPU",
                        "lost by the second draw, Vulkan", "CPU = Vulkan", "as expected"}}};
  for (const IdenticalControl& c : identical_controls(table))
    control.table.push_back({c.format, fmt::format("{:g}", c.angle_deg), fmt::format("{:g}", c.constant),
                             fmt::format("{:g}", c.wrong_cpu), fmt::format("{:g}", c.wrong_vk),
                             c.cpu_vk_agree ? "yes" : "no", c.as_expected ? "yes" : "NO"});
  write_index_html(
      dir, "Polygon offset and z-fighting",
      {{"Z-fighting against far/near",
        "A decal drawn after its base with compare op Less; the fraction of the decal's pixels that the base wins, per "
        "depth "
        "format, without and with polygon offset. near = far / ratio.",
        far_near_charts},
       {"Smallest offset against depth slope",
        "For each viewing angle, the smallest constant factor (slope 0) and the smallest slope factor (constant 0) at "
        "which "
        "neither backend shows a wrong pixel; missing points: no tried value was enough.",
        {"min_constant_vs_angle", "min_slope_vs_angle", "wrong_vs_angle"}},
       {"Clamp", "A large offset limited by depthBiasClamp.", {"clamp"}},
       control,
       {"r per depth format",
        "Measured from the stored depth of a flat plane at depth 0.375 with constantFactor 1 against 0, divided by the "
        "spec bound, beside lavapipe's predicted r (depth_r.json: r_cpu, r_vulkan, predicted, spec_bound).",
        {"depth_r"}}},
      {kPolygonOffsetCsv, "depth_r.json", "polygon_offset.json"});
}

}  // namespace rastercmp::experiments
