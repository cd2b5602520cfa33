#include "cpu_raster/exact/setup_methods.hpp"

#include <string>

#include "model/errors.hpp"

namespace rastercmp::cpu {
namespace {

[[noreturn]] void unknown_name(const MethodChoice& choice, const char* known) {
  throw UsageError("method " + choice.stage + "=" + choice.name + ": unknown name for stage \"" + choice.stage +
                   "\"; known: " + known);
}

SnapRounding parse_snap(const MethodChoice& choice) {
  if (choice.name == "round_nearest_even") return SnapRounding::NearestEven;
  if (choice.name == "round_half_away") return SnapRounding::HalfAwayFromZero;
  unknown_name(choice, "round_nearest_even, round_half_away");
}

TieBreak parse_tie_break(const MethodChoice& choice) {
  if (choice.name == "top_left") return TieBreak::TopLeft;
  if (choice.name == "none") return TieBreak::None;
  unknown_name(choice, "top_left, none");
}

}  // namespace

SetupMethods parse_setup_methods(const std::vector<MethodChoice>& choices) {
  SetupMethods methods;
  for (const MethodChoice& choice : choices) {
    if (choice.stage == "snap") {
      methods.snap = parse_snap(choice);
    } else if (choice.stage == "tie_break") {
      methods.tie_break = parse_tie_break(choice);
    } else {
      throw UsageError("method " + choice.stage + "=" + choice.name + ": unknown stage \"" + choice.stage +
                       "\"; the exact path knows snap and tie_break, docs/methods.md lists the classic stages");
    }
  }
  return methods;
}

}  // namespace rastercmp::cpu
