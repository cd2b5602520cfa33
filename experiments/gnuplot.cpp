#include "experiments/gnuplot.hpp"

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
  const std::string gnuplot = find_gnuplot();
  write_text_file_atomic((fs::path(dir) / (name + ".dat")).string(), data_text(blocks));
  write_text_file_atomic((fs::path(dir) / (name + ".gp")).string(),
                         "# rastercmp chart; run: gnuplot -e \"set terminal svg; set output 'x.svg'; DATA='" + name +
                             ".dat'\" " + name + ".gp\n" + "set key noenhanced\n" + body);
  run_terminal(gnuplot, dir, name, "svg size 960,640 dynamic font 'sans,13' background '#ffffff'", "svg");
  run_terminal(gnuplot, dir, name, "pngcairo size 1200,800 font 'sans,12'", "png");
}

}  // namespace rastercmp::experiments
