// rastercmp docs update|check DOC [--work DIR] [--timed fail|report]
// Runs every command named by DOC's table markers (experiments/doc_tables.hpp) once, with this
// executable and --out in a work folder, then rewrites DOC's tables (update) or compares them
// (check: exit 1 listing each drifted cell, deterministic and timed apart; 0 when all agree).
#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "app/commands.hpp"
#include "experiments/doc_tables.hpp"
#include "model/errors.hpp"
#include "model/file_read.hpp"
#include "model/image_io.hpp"

extern char** environ;

namespace rastercmp::app {
namespace {
namespace fs = std::filesystem;
using experiments::CellDrift;
using experiments::DocCommand;
using experiments::DocMarker;
using experiments::MarkdownTable;

struct DocsOptions {
  std::string doc;
  std::string work;  // empty: a temporary folder, removed afterwards
  std::string timed = "fail";  // check: "fail" (timed drift exits 1) or "report" (listed, exit by deterministic drift)
};

// Runs `rastercmp ARGS --out OUT` with this executable; output to LOG. Returns the exit status.
int run_self(const std::vector<std::string>& args, const std::string& out, const std::string& log) {
  std::vector<std::string> argv = {"rastercmp"};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.push_back("--out");
  argv.push_back(out);
  std::vector<char*> c_argv;
  for (std::string& a : argv) c_argv.push_back(a.data());
  c_argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int err = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, c_argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) throw EnvironmentError(fmt::format("cannot start /proc/self/exe: error {}", err));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw EnvironmentError("waitpid failed");
  return WIFEXITED(status) ? WEXITSTATUS(status) : kExitInternal;
}

std::string tail(const std::string& path, size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) out += "    " + all[i] + "\n";
  return out;
}

// Runs the commands (dependencies come first in the list); returns each one's output folder.
std::vector<std::string> run_commands(const std::vector<DocCommand>& commands, const fs::path& work) {
  std::vector<std::string> outs;
  double total = 0;
  for (size_t i = 0; i < commands.size(); ++i) {
    std::vector<std::string> args = commands[i].args;
    for (size_t a = 0; a < args.size(); ++a)
      if (commands[i].dependencies[a]) args[a] = outs[commands[i].dependencies[a] - 1];
    const std::string out = (work / fmt::format("run-{}", i + 1)).string();
    const std::string log = out + ".log";
    const auto start = std::chrono::steady_clock::now();
    const int rc = run_self(args, out, log);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    total += seconds;
    fmt::print(stderr, "docs: {} ({:.1f} s)\n", commands[i].key, seconds);
    if (rc != 0) {
      fmt::print(stderr, "docs: `{}` exited {}; the end of its output ({}):\n{}", commands[i].key, rc, log,
                 tail(log, 20));
      throw EnvironmentError(fmt::format("`{}` failed (exit {})", commands[i].key, rc));
    }
    outs.push_back(out);
  }
  fmt::print(stderr, "docs: {} commands in {:.1f} s\n", commands.size(), total);
  return outs;
}

void print_drifts(const std::vector<CellDrift>& drifts, bool timed) {
  for (const CellDrift& d : drifts)
    if (d.timed == timed)
      fmt::print("  {}, {}, column \"{}\": documented {}, measured {}\n", d.table, d.row, d.column, d.documented,
                 d.measured);
}

int docs_main(const DocsOptions& o, bool update) {
  const std::string text = read_bounded_file(o.doc, 16u << 20, "a markdown document");
  const std::vector<DocMarker> markers = experiments::parse_doc_markers(text, o.doc);
  if (markers.empty()) throw UsageError(o.doc + ": no `<!-- table: NAME from: rastercmp ARGS -->` marker");
  std::vector<DocCommand> commands;
  std::vector<size_t> command_of;
  for (const DocMarker& m : markers)
    command_of.push_back(experiments::add_doc_command(commands, m.command, fmt::format("{}:{}: ", o.doc, m.begin_line)));
  // The documented tables are read before anything runs, so a malformed one fails at once.
  std::vector<MarkdownTable> documented;
  for (const DocMarker& m : markers) documented.push_back(experiments::documented_table(text, m, o.doc));

  const bool temporary = o.work.empty();
  fs::path work = o.work;
  if (temporary) {
    std::string pattern = (fs::temp_directory_path() / "rastercmp-docs-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw EnvironmentError("cannot make a temporary folder in " + pattern);
    work = pattern;
  } else {
    fs::create_directories(work);
  }
  struct Cleanup {
    fs::path dir;
    bool on;
    ~Cleanup() {
      std::error_code ec;
      if (on) fs::remove_all(dir, ec);
    }
  } cleanup{work, temporary};

  const std::vector<std::string> outs = run_commands(commands, work);
  std::map<std::string, MarkdownTable> measured;
  for (size_t i = 0; i < markers.size(); ++i)
    measured[markers[i].name] = experiments::measured_table(outs[command_of[i]], markers[i], o.doc);

  if (update) {
    const std::string rewritten = experiments::rewrite_doc(text, markers, measured, o.doc);
    if (rewritten != text) write_text_file_atomic(o.doc, rewritten);
    fmt::print("docs update: {}: {} tables from {} commands{}\n", o.doc, markers.size(), commands.size(),
               rewritten == text ? ", already current" : ", rewritten");
    return kExitOk;
  }
  std::vector<CellDrift> drifts;
  for (size_t i = 0; i < markers.size(); ++i) {
    auto d = experiments::compare_tables(markers[i].name, documented[i], measured[markers[i].name]);
    drifts.insert(drifts.end(), d.begin(), d.end());
  }
  size_t timed = 0;
  for (const CellDrift& d : drifts) timed += d.timed;
  const size_t exact = drifts.size() - timed;
  fmt::print("docs check: {}: {} tables from {} commands: {} deterministic cells drifted, {} timed cells whose "
             "interval is apart from the documented one\n",
             o.doc, markers.size(), commands.size(), exact, timed);
  if (exact) {
    fmt::print("deterministic drift (the documented value is not what the command measures):\n");
    print_drifts(drifts, false);
  }
  if (timed) {
    fmt::print("timed drift (the interval measured here and the documented one are disjoint; timings depend on the "
               "host and its load: re-measure on a quiet host: make docs-tables):\n");
    print_drifts(drifts, true);
  }
  if (timed && o.timed == "report")
    fmt::print("(--timed report: the timed drift above is listed, not failed)\n");
  return exact || (timed && o.timed == "fail") ? kExitMismatch : kExitOk;
}

}  // namespace

void add_docs_command(CLI::App& app, int& exit_code) {
  CLI::App* docs = app.add_subcommand(
      "docs", "regenerate or check the measured tables of a document (markers `<!-- table: NAME from: rastercmp ARGS -->`)");
  docs->require_subcommand(1);
  auto options = std::make_shared<DocsOptions>();
  const auto add = [&](const char* name, const char* help, bool update) {
    CLI::App* cmd = docs->add_subcommand(name, help);
    cmd->add_option("doc", options->doc, "the markdown document, e.g. docs/experiments.md")->required();
    cmd->add_option("--work", options->work,
                    "folder for the commands' outputs (kept); default a temporary folder, removed afterwards");
    if (!update)
      cmd->add_option("--timed", options->timed,
                      "fail: a timed median outside the new interval exits 1, as deterministic drift does; report: "
                      "list it, exit by deterministic drift alone")
          ->check(CLI::IsMember({"fail", "report"}))
          ->capture_default_str();
    cmd->callback([options, update, &exit_code] { exit_code = docs_main(*options, update); });
  };
  add("update", "run each marker's command once and rewrite the tables in place", true);
  add("check",
      "run each marker's command once and compare: exit 1 listing every drifted cell (deterministic cells must be "
      "equal, timed medians inside the measured interval), 0 when all agree",
      false);
}

}  // namespace rastercmp::app
