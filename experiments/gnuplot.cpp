#include "experiments/gnuplot.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include <fmt/core.h>

#include "model/errors.hpp"
#include "model/image_io.hpp"

namespace rastercmp::experiments {
namespace fs = std::filesystem;
namespace {

std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string data_text(const std::vector<DataBlock>& blocks) {
  std::string text;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (b) text += "\n\n";
    text += "# " + blocks[b].title + "\n";
    for (const auto& row : blocks[b].rows) {
      for (size_t i = 0; i < row.size(); ++i) text += (i ? " " : "") + row[i];
      text += "\n";
    }
    if (blocks[b].rows.empty()) text += "NaN NaN\n";  // gnuplot needs a point per block
  }
  return text;
}

// 16 series styles: distinct colours, and dash and point types that cycle with other periods, so
// neighbouring series differ in all three. Line width and point size shrink over each group of four,
// so series that coincide (D24 over D32) still show one inside the other.
constexpr const char* kSeriesColours[kSeriesStyles] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
                                                       "#e377c2", "#17becf", "#000000", "#bcbd22", "#7f7f7f", "#aec7e8",
                                                       "#ff9896", "#98df8a", "#ffbb78", "#c5b0d5"};
constexpr int kPointTypes[] = {7, 5, 9, 11, 13, 2, 3, 1, 6, 4, 8, 10, 12, 14};

std::string series_style_commands() {
  std::string text;
  for (int k = 0; k < kSeriesStyles; ++k)
    text += fmt::format("set linetype {} lc rgb '{}' lw {} dt {} pt {} ps {}\n", k + 1, kSeriesColours[k],
                        3.5 - 0.5 * (k % 4), k % 4 + 1, kPointTypes[k % 14], 2.0 - 0.3 * (k % 4));
  return text + fmt::format("set linetype cycle {}\n", kSeriesStyles);
}

void run_terminal(const std::string& gnuplot, const std::string& dir, const std::string& name,
                  const std::string& terminal, const std::string& extension) {
  const std::string final_path = (fs::path(dir) / (name + "." + extension)).string();
  const std::string temp_path = final_path + ".tmp";
  const std::string setup = fmt::format("set terminal {}; set output {}; DATA={}", terminal, gp_quote(temp_path),
                                        gp_quote((fs::path(dir) / (name + ".dat")).string()));
  const std::string command = fmt::format("{} -e {} {} 2>&1", shell_quote(gnuplot), shell_quote(setup),
                                          shell_quote((fs::path(dir) / (name + ".gp")).string()));
  std::FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) throw EnvironmentError("cannot start gnuplot (" + gnuplot + ")");
  std::string messages;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, pipe)) messages += buffer;
  const int status = ::pclose(pipe);
  if (status != 0 || !fs::exists(temp_path)) throw std::runtime_error("gnuplot failed on " + name + ".gp: " + messages);
  fs::rename(temp_path, final_path);
}

}  // namespace

std::string noenhanced_text(const std::string& body) {
  std::istringstream in(body);
  std::string out;
  for (std::string line; std::getline(in, line);) {
    for (const char* command : {"set title ", "set xlabel ", "set ylabel ", "set cblabel ", "set label "})
      if (line.rfind(command, 0) == 0 && line.find("noenhanced") == std::string::npos) line += " noenhanced";
    out += line + "\n";
  }
  return out;
}

double log_axis_floor(const std::vector<double>& values) {
  double smallest = 0;
  for (double v : values)
    if (v > 0 && (smallest == 0 || v < smallest)) smallest = v;
  return smallest == 0 ? 0.1 : std::pow(10.0, std::floor(std::log10(smallest)) - 1);
}

std::string zero_tic_command(const std::string& axis, double floor) {
  return fmt::format("set {}tics add ('0' {:g})\n", axis, floor);
}

SymlogAxis::SymlogAxis(const std::vector<double>& values) {
  double smallest = 0;
  for (double v : values)
    if (v != 0 && std::isfinite(v) && (smallest == 0 || std::fabs(v) < smallest)) smallest = std::fabs(v);
  c = smallest == 0 ? 1 : smallest;
}

double SymlogAxis::position(double x) const {
  const double m = std::fabs(x);
  if (m < c) return x / c;
  return std::copysign(1 + std::log10(m / c), x);
}

std::string SymlogAxis::tics_command(const std::string& axis, const std::vector<std::string>& labels) const {
  std::string text = "set " + axis + "tics (";
  for (size_t i = 0; i < labels.size(); ++i)
    text += fmt::format("{}{} {:.10g}", i ? ", " : "", gp_quote(labels[i]), position(std::stod(labels[i])));
  return text + ")\n";
}

bool only_zeros(const std::vector<DataBlock>& blocks, size_t column) {
  bool zero = false;
  for (const DataBlock& block : blocks)
    for (const auto& row : block.rows) {
      if (row.size() <= column) continue;
      char* end = nullptr;
      const double v = std::strtod(row[column].c_str(), &end);
      if (end == row[column].c_str() || *end != '\0') continue;  // not a number
      if (std::isnan(v)) continue;
      if (v != 0) return false;
      zero = true;
    }
  return zero;
}

std::string gp_quote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  return quoted + "'";
}

std::string find_gnuplot() {
  if (const char* env = std::getenv("RASTERCMP_GNUPLOT"); env && *env) {
    if (fs::exists(env)) return env;
    throw EnvironmentError(std::string("RASTERCMP_GNUPLOT=") + env + " does not exist");
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / "gnuplot";
    if (fs::exists(candidate)) return candidate.string();
  }
  throw EnvironmentError("gnuplot is not installed (scripts/setup.sh installs gnuplot-nox); charts need it");
}

void render_chart(const std::string& dir, const std::string& name, const std::vector<DataBlock>& blocks,
                  const std::string& body) {
  render_chart_sized(dir, name, blocks, body, 1200, 800);
}

void render_chart_sized(const std::string& dir, const std::string& name, const std::vector<DataBlock>& blocks,
                        const std::string& body, int width, int height) {
  const std::string gnuplot = find_gnuplot();
  write_text_file_atomic((fs::path(dir) / (name + ".dat")).string(), data_text(blocks));
  write_text_file_atomic((fs::path(dir) / (name + ".gp")).string(),
                         "# rastercmp chart; run: gnuplot -e \"set terminal svg; set output 'x.svg'; DATA='" + name +
                             ".dat'\" " + name + ".gp\n" + "set key noenhanced\n" + series_style_commands() +
                             noenhanced_text(body));
  run_terminal(gnuplot, dir, name,
               fmt::format("svg size {},{} dynamic font 'sans,13' background '#ffffff'", width * 4 / 5, height * 4 / 5),
               "svg");
  run_terminal(gnuplot, dir, name, fmt::format("pngcairo size {},{} font 'sans,12'", width, height), "png");
}

}  // namespace rastercmp::experiments
