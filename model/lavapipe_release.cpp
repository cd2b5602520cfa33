#include "model/lavapipe_release.hpp"

#include <array>
#include <charconv>
#include <cstdlib>

namespace rastercmp {
namespace {

using enum LavapipeRule;

// What changed, oldest first (docs/lavapipe-rules.md §8 has the evidence for each row).
constexpr std::array kRuleChanges = {
    LavapipeRuleChange{
        LineRoundHalfToEven, {23, 1, 0}, "util: Implement util_iround with lrintf unconditionally", "§8.1"},
    LavapipeRuleChange{LineGuardBand, {23, 2, 0}, "aux/draw: add guardband clipping for lines", "§8.2"},
    LavapipeRuleChange{
        BresenhamEndSignTests, {23, 2, 0}, "llvmpipe: fix some corner cases with line rendering", "§8.3"},
    LavapipeRuleChange{UnormBiasHalfUnit, {25, 2, 0}, "llvmpipe: Improve depth bias rounding workaround", "§8.4"},
    LavapipeRuleChange{MsaaLineDepthAtCentre,
                       {25, 3, 0},
                       "llvmpipe: Fix attribute interpolation setup when rendering lines with msaa",
                       "§8.5"},
    LavapipeRuleChange{NoMsaaRegionLeak, {25, 3, 0}, "llvmpipe: fix incorrect scissor planes", "§8.6"},
    LavapipeRuleChange{RasterizerOverflowReworked, {26, 2, 0}, "llvmpipe: fix overflow in rasterizer", "§8.7"},
};
static_assert(kRuleChanges.size() == size_t(LavapipeRule::Count), "one row per rule");

// The modelled releases, oldest first.
constexpr std::array kReleases = {
    LavapipeRelease{"lavapipe-22.3", {22, 3, 6}, "Debian 12 (bookworm)"},
    LavapipeRelease{"lavapipe-25.0", {25, 0, 7}, "Debian 13 (trixie)"},
    LavapipeRelease{"lavapipe-26.2", {26, 2, 6}, "Debian unstable (sid)"},
};

// A version as a number on one scale, for "nearest": minor and patch never reach 1000.
int64_t ordinal(const MesaVersion& v) { return int64_t(v.major) * 1000000 + int64_t(v.minor) * 1000 + v.patch; }

std::optional<uint32_t> read_number(std::string_view& text) {
  uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end == text.data()) return std::nullopt;
  text.remove_prefix(size_t(end - text.data()));
  return value;
}

}  // namespace

std::string MesaVersion::to_string() const {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

std::optional<MesaVersion> parse_mesa_version(std::string_view driver_info) {
  constexpr std::string_view kMesa = "Mesa ";
  const size_t at = driver_info.find(kMesa);
  if (at == std::string_view::npos) return std::nullopt;
  std::string_view text = driver_info.substr(at + kMesa.size());
  MesaVersion v;
  const auto major = read_number(text);
  if (!major || text.empty() || text.front() != '.') return std::nullopt;
  text.remove_prefix(1);
  const auto minor = read_number(text);
  if (!minor) return std::nullopt;
  v.major = *major;
  v.minor = *minor;
  if (!text.empty() && text.front() == '.') {
    text.remove_prefix(1);
    if (const auto patch = read_number(text)) v.patch = *patch;
  }
  if (v.minor >= 1000 || v.patch >= 1000) return std::nullopt;
  return v;
}

std::span<const LavapipeRuleChange> lavapipe_rule_changes() { return kRuleChanges; }

LavapipeRules LavapipeRules::of(const MesaVersion& version) {
  LavapipeRules rules;
  for (const LavapipeRuleChange& change : kRuleChanges)
    if (change.introduced <= version) rules.bits_ |= 1u << uint32_t(change.rule);
  return rules;
}

std::span<const LavapipeRelease> lavapipe_releases() { return kReleases; }

const LavapipeRelease& default_lavapipe_release() { return kReleases.back(); }

const LavapipeRelease* find_lavapipe_release(std::string_view profile) {
  for (const LavapipeRelease& r : kReleases)
    if (profile == r.profile) return &r;
  return nullptr;
}

LavapipeReleaseChoice lavapipe_release_for_driver(std::string_view driver_info) {
  LavapipeReleaseChoice choice;
  const std::optional<MesaVersion> version = parse_mesa_version(driver_info);
  if (!version) {
    choice.release = &default_lavapipe_release();
    choice.warning = "the driver's version (\"" + std::string(driver_info) + "\") names no Mesa release: judged by " +
                     choice.release->profile + " (Mesa " + choice.release->version.to_string() + ")";
    return choice;
  }
  const LavapipeRelease* nearest = &kReleases.front();
  for (const LavapipeRelease& r : kReleases) {
    if (r.version.major == version->major && r.version.minor == version->minor) {
      choice.release = &r;
      return choice;
    }
    if (std::llabs(ordinal(r.version) - ordinal(*version)) < std::llabs(ordinal(nearest->version) - ordinal(*version)))
      nearest = &r;
  }
  choice.release = nearest;
  choice.warning = "lavapipe Mesa " + version->to_string() + " is not a modelled release: judged by " +
                   nearest->profile + " (Mesa " + nearest->version.to_string() +
                   "), the nearest; differences may be the driver's changes, not faults";
  return choice;
}

}  // namespace rastercmp
