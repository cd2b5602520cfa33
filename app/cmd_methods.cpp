// rastercmp methods [--json]: every stage --method takes and every name of each, with one line on
// what it does, the lecture notes' section it comes from (by title) and the docs section that
// describes it (cpu_raster/classic/method_registry.hpp, the one list).
#include <memory>
#include <string>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "cpu_raster/cpu_raster.hpp"
#include "model/errors.hpp"

namespace rastercmp::app {
namespace {

using cpu::classic::MethodInfo;
using cpu::classic::StageInfo;

// Pseudo-depth's precision at its far plane: eye distance per stored step, D16 and X8_D24.
std::string precision_note(const MethodInfo& m) {
  const double far_distance = cpu::classic::pseudo_depth_far(m.name);
  if (far_distance == 0) return "";
  return fmt::format("one depth step at far {:g} is {:.3g} eye units in D16, {:.3g} in D24", far_distance,
                     cpu::classic::pseudo_depth_step_at_far(far_distance, 16),
                     cpu::classic::pseudo_depth_step_at_far(far_distance, 24));
}

std::string source_text(const MethodInfo& m) {
  const std::string names = cpu::classic::method_names(m.stage);
  const bool is_default = names.substr(0, names.find(',')) == m.name;
  if (m.notes.empty())
    return fmt::format("{}, {}", is_default ? "lavapipe's rule" : "ablation of lavapipe's rule", m.doc);
  return fmt::format("notes \"{}\", docs/methods.md \"{}\"", m.notes, m.doc);
}

nlohmann::json methods_json() {
  nlohmann::json stages = nlohmann::json::array();
  for (const StageInfo& s : cpu::classic::method_stages()) {
    nlohmann::json names = nlohmann::json::array();
    for (const MethodInfo& m : cpu::classic::method_registry()) {
      if (m.stage != s.stage) continue;
      nlohmann::json entry{{"name", m.name}, {"summary", m.summary}, {"notes_section", m.notes}, {"doc", m.doc}};
      if (const std::string precision = precision_note(m); !precision.empty()) entry["precision"] = precision;
      names.push_back(entry);
    }
    stages.push_back({{"stage", s.stage}, {"summary", s.summary}, {"methods", names}});
  }
  return nlohmann::json{{"stages", stages}};
}

int run_methods(bool json) {
  if (json) {
    fmt::print("{}\n", methods_json().dump(2));
    return kExitOk;
  }
  for (const StageInfo& s : cpu::classic::method_stages()) {
    fmt::print("{}: {}\n", s.stage, s.summary);
    for (const MethodInfo& m : cpu::classic::method_registry()) {
      if (m.stage != s.stage) continue;
      fmt::print("  {:<20} {} ({})\n", m.name, m.summary, source_text(m));
      if (const std::string precision = precision_note(m); !precision.empty())
        fmt::print("  {:<20} {}\n", "", precision);
    }
  }
  fmt::print(
      "Select with --method STAGE=NAME (repeatable) or a scene's \"methods\" object; the first name of a "
      "stage is the default.\n");
  return kExitOk;
}

}  // namespace

void add_methods_command(CLI::App& app, int& exit_code) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("methods", "list every --method stage and name, with its lecture-note section");
  cmd->add_flag("--json", *json, "print JSON instead of text");
  cmd->callback([json, &exit_code] { exit_code = run_methods(*json); });
}

}  // namespace rastercmp::app
