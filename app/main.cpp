// rastercmp: the command-line front end. Exit codes: README "Exit codes" (model/errors.hpp).
#include <csignal>
#include <cstdio>
#include <exception>
#include <string>

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include "app/commands.hpp"
#include "model/errors.hpp"

int main(int argc, char** argv) {
  using namespace rastercmp;
  // A write past a file-size limit (ulimit -f) then fails with EFBIG, as one on a full disk fails
  // with ENOSPC, and the writers report it (exit 2, nothing half-written under a final name)
  // instead of the process dying of SIGXFSZ with no message.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"rastercmp: a CPU rasterizer and lavapipe, compared pixel by pixel"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("rastercmp ") + RASTERCMP_VERSION);
  int exit_code = kExitOk;
  app::add_devices_command(app, exit_code);
  app::add_methods_command(app, exit_code);
  app::add_render_command(app, exit_code);
  app::add_import_command(app, exit_code);
  app::add_capture_command(app, exit_code);
  app::add_compare_command(app, exit_code);
  app::add_explain_command(app, exit_code);
  app::add_conformance_command(app, exit_code);
  app::add_merge_command(app, exit_code);
  app::add_bench_command(app, exit_code);
  app::add_sweep_command(app, exit_code);
  app::add_chart_command(app, exit_code);
  app::add_docs_command(app, exit_code);
  app::add_soak_command(app, exit_code);
  app::add_reduce_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help or the parse error
    return code == 0 ? kExitOk : kExitBadInput;
  } catch (const InputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const UsageError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kExitBadInput;
  } catch (const EnvironmentError& e) {
    fmt::print(stderr, "environment: {}\n", e.what());
    return kExitEnvironment;
  } catch (const NotSupportedError& e) {
    fmt::print(stderr, "not supported: {}\n", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    fmt::print(stderr, "internal error: {}\n", e.what());
    return kExitInternal;
  }
  return exit_code;
}
