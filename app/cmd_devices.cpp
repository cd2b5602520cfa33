// rastercmp devices [--json]: the Vulkan devices, what they can render, and whether lavapipe
// fuses multiply-adds on this host (docs/lavapipe-rules.md §1.3, §7.1).
#include <memory>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>  // fmt::join (fmt 11 has it only there)
#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "model/errors.hpp"
#include "model/host.hpp"
#include "model/lavapipe_release.hpp"
#include "vk_reference/vk_reference.hpp"

namespace rastercmp::app {
namespace {

std::vector<std::string> depth_format_names(const DeviceInfo& device) {
  std::vector<std::string> names;
  for (DepthFormat format : device.depth_formats) names.emplace_back(to_string(format));
  return names;
}

const char* yes_no(bool value) { return value ? "yes" : "no"; }

std::string device_text(const DeviceInfo& d, bool host_fma) {
  std::string text = fmt::format("{}: {} [{}]\n", d.index, d.name, d.type);
  const std::string driver = d.driver_name.empty() ? std::string("(driver properties not reported)")
                                                   : fmt::format("{}, {}", d.driver_name, d.driver_info);
  const auto line = [&text](const char* label, const std::string& value) {
    text += fmt::format("   {:<23}{}\n", label, value);
  };
  line("driver:", fmt::format("{} (Vulkan {})", driver, d.api_version));
  line("subPixelPrecisionBits:", std::to_string(d.sub_pixel_precision_bits));
  const std::vector<std::string> formats = depth_format_names(d);
  line("depth formats:", formats.empty() ? std::string("none") : fmt::format("{}", fmt::join(formats, ", ")));
  line("sample counts:", fmt::format("{}", fmt::join(d.sample_counts, ", ")));
  if (d.is_lavapipe) {
    line("host FMA:", fmt::format("{} (lavapipe fuses: {})", yes_no(host_fma), yes_no(d.fma)));
    const LavapipeReleaseChoice choice = lavapipe_release_for_driver(d.driver_info);
    line("lavapipe profile:", choice.warning.empty()
                                  ? std::string(choice.release->profile)
                                  : fmt::format("{} (warning: {})", choice.release->profile, choice.warning));
  }
  return text;
}

nlohmann::json device_json(const DeviceInfo& d) {
  return nlohmann::json{
      {"index", d.index},
      {"name", d.name},
      {"type", d.type},
      {"driver_name", d.driver_name},
      {"driver_info", d.driver_info},
      {"api_version", d.api_version},
      {"sub_pixel_precision_bits", d.sub_pixel_precision_bits},
      {"depth_formats", depth_format_names(d)},
      {"sample_counts", d.sample_counts},
      {"is_lavapipe", d.is_lavapipe},
      {"fma", d.fma},
      {"lavapipe_profile", d.is_lavapipe ? nlohmann::json(lavapipe_release_for_driver(d.driver_info).release->profile)
                                         : nlohmann::json(nullptr)}};
}

int run_devices(bool json) {
  const std::vector<DeviceInfo> devices = list_vulkan_devices();  // EnvironmentError: exit 3
  const bool host_fma = host_cpu_has_fma();
  if (json) {
    nlohmann::json out{{"host_cpu_fma", host_fma}, {"devices", nlohmann::json::array()}};
    for (const DeviceInfo& d : devices) out["devices"].push_back(device_json(d));
    fmt::print("{}\n", out.dump(2));
    return kExitOk;
  }
  for (const DeviceInfo& d : devices) fmt::print("{}", device_text(d, host_fma));
  return kExitOk;
}

}  // namespace

void add_devices_command(CLI::App& app, int& exit_code) {
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("devices", "list the Vulkan devices and what they can render");
  cmd->add_flag("--json", *json, "print JSON instead of a table");
  cmd->callback([json, &exit_code] { exit_code = run_devices(*json); });
}

}  // namespace rastercmp::app
