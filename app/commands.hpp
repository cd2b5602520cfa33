// Each command lives in its own file and registers itself on the CLI11 app.
// A command's callback stores its exit code in `exit_code`; errors are thrown and mapped to
// exit codes in main.cpp (model/errors.hpp). Options shared by the rendering commands
// (--profile, --fma, --method, --threads, --device, --validate) live in app/options.hpp.
#pragma once

#include <CLI/CLI.hpp>

namespace rastercmp::app {

void add_devices_command(CLI::App& app, int& exit_code);
void add_methods_command(CLI::App& app, int& exit_code);
void add_render_command(CLI::App& app, int& exit_code);
void add_import_command(CLI::App& app, int& exit_code);
void add_capture_command(CLI::App& app, int& exit_code);
void add_compare_command(CLI::App& app, int& exit_code);
void add_explain_command(CLI::App& app, int& exit_code);
void add_conformance_command(CLI::App& app, int& exit_code);
void add_merge_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_sweep_command(CLI::App& app, int& exit_code);
void add_chart_command(CLI::App& app, int& exit_code);
void add_soak_command(CLI::App& app, int& exit_code);
void add_reduce_command(CLI::App& app, int& exit_code);
void add_docs_command(CLI::App& app, int& exit_code);

}  // namespace rastercmp::app
