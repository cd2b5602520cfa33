// The lavapipe releases the `lavapipe` profile reproduces, and the one table of what changed
// between them (docs/lavapipe-rules.md §8). A stage asks the release's LavapipeRules whether a rule
// holds; no stage compares versions.
//
// The profile is chosen from the driver it meets (VkPhysicalDeviceDriverProperties::driverInfo,
// "Mesa 25.0.7 (LLVM 19.1.7)"): the modelled release of the same major.minor, else the nearest
// one, with a warning that every output carries. `--profile lavapipe-25.0` forces one.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace rastercmp {

struct MesaVersion {
  uint32_t major = 0, minor = 0, patch = 0;
  friend auto operator<=>(const MesaVersion&, const MesaVersion&) = default;
  std::string to_string() const;
};

// "Mesa 25.0.7", "Mesa 25.0.7 (LLVM 19.1.7)", "Mesa 26.2.6-1 (git-...)": the first "Mesa X.Y[.Z]".
std::optional<MesaVersion> parse_mesa_version(std::string_view driver_info);

// A behaviour of lavapipe that one release has and an earlier one has not. Each is a rule of
// docs/lavapipe-rules.md §8; the stage that implements it cites the same section.
enum class LavapipeRule : uint32_t {
  LineRoundHalfToEven,         // util_iround is lrintf: line snapping and Bresenham width tie to even (§8.1)
  LineGuardBand,               // lines clipped against z, w and user planes only, cut by the draw region (§8.2)
  BresenhamEndSignTests,       // Bresenham ends decided by per-direction sign tests (§8.3)
  UnormBiasHalfUnit,           // UNORM depth bias constant: fl(c ± 0.5) units, not 2c (§8.4)
  MsaaLineDepthAtCentre,       // multisampled lines: no half-pixel offset in the depth plane (§8.5)
  NoMsaaRegionLeak,            // scissor planes exact at every sample count, no 127/256 px leak (§8.6)
  RasterizerOverflowReworked,  // llvmpipe's wrapping integer set-up changed: not modelled, refused (§8.7)
  Count,
};

// One row of the table: the rule, the Mesa release that first shipped it, the change, the section.
struct LavapipeRuleChange {
  LavapipeRule rule;
  MesaVersion introduced;
  const char* mesa_change;  // the Mesa commit's title
  const char* section;      // docs/lavapipe-rules.md
};

std::span<const LavapipeRuleChange> lavapipe_rule_changes();

// The set of rules one release follows.
class LavapipeRules {
 public:
  constexpr LavapipeRules() = default;
  static LavapipeRules of(const MesaVersion& version);  // every change introduced at or before it
  bool has(LavapipeRule rule) const { return (bits_ >> uint32_t(rule)) & 1u; }
  friend bool operator==(const LavapipeRules&, const LavapipeRules&) = default;

 private:
  uint32_t bits_ = 0;
};

// A modelled release: what the profile reproduces bit for bit.
struct LavapipeRelease {
  const char* profile;  // the --profile name: "lavapipe-22.3"
  MesaVersion version;  // the build it was verified against
  const char* system;   // where users meet it: "Debian 12 (bookworm)"
  LavapipeRules rules() const { return LavapipeRules::of(version); }
};

std::span<const LavapipeRelease> lavapipe_releases();  // oldest first
const LavapipeRelease& default_lavapipe_release();     // when no driver says which: the newest

// "lavapipe-25.0" → its release; nullptr for another name.
const LavapipeRelease* find_lavapipe_release(std::string_view profile);

// The release a driver is judged by, with the reason when it is not the driver's own.
struct LavapipeReleaseChoice {
  const LavapipeRelease* release = nullptr;
  std::string warning;  // empty: the driver is the modelled release (same major.minor)
};

// driver_info as a lavapipe device reports it; an unparsable string gives the default release
// with a warning saying so.
LavapipeReleaseChoice lavapipe_release_for_driver(std::string_view driver_info);

}  // namespace rastercmp
