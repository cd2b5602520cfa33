#include "cpu_raster/classic/classic_methods.hpp"

#include <array>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "cpu_raster/classic/method_registry.hpp"

namespace rastercmp::cpu::classic {
namespace {

template <class Enum, size_t N>
using NameTable = std::array<std::pair<std::string_view, Enum>, N>;

constexpr NameTable<ClipMethod, 7> kClip{{{"exact", ClipMethod::Exact},
                                          {"sutherland_hodgman", ClipMethod::SutherlandHodgman},
                                          {"weiler_atherton", ClipMethod::WeilerAtherton},
                                          {"cohen_sutherland", ClipMethod::CohenSutherland},
                                          {"cohen_sutherland_3d", ClipMethod::CohenSutherland3d},
                                          {"liang_barsky", ClipMethod::LiangBarsky},
                                          {"cyrus_beck", ClipMethod::CyrusBeck}}};
constexpr NameTable<FillMethod, 6> kFill{{{"exact", FillMethod::Exact},
                                          {"scanline", FillMethod::Scanline},
                                          {"float_edge", FillMethod::FloatEdge},
                                          {"even_odd", FillMethod::EvenOdd},
                                          {"winding", FillMethod::Winding},
                                          {"flood", FillMethod::Flood}}};
constexpr NameTable<LineMethod, 3> kLine{
    {{"exact", LineMethod::Exact}, {"dda", LineMethod::Dda}, {"bresenham", LineMethod::Bresenham}}};
constexpr NameTable<DepthMethod, 7> kDepth{{{"exact", DepthMethod::Exact},
                                            {"no_fma", DepthMethod::NoFma},
                                            {"bilinear", DepthMethod::Bilinear},
                                            {"perspective_correct", DepthMethod::PerspectiveCorrect},
                                            {"pseudo_depth_75", DepthMethod::PseudoDepth},
                                            {"pseudo_depth_750", DepthMethod::PseudoDepth},
                                            {"pseudo_depth_7500", DepthMethod::PseudoDepth}}};
constexpr NameTable<VisibilityMethod, 3> kVisibility{
    {{"zbuffer", VisibilityMethod::ZBuffer}, {"painter", VisibilityMethod::Painter}, {"bsp", VisibilityMethod::Bsp}}};
constexpr NameTable<CullMethod, 2> kCull{
    {{"exact", CullMethod::Exact}, {"normal_dot_view", CullMethod::NormalDotView}}};

// The registry has checked the name; a name missing here is a registry entry without code.
template <class Enum, size_t N>
Enum lookup(const MethodChoice& choice, const NameTable<Enum, N>& table) {
  for (const auto& [name, value] : table)
    if (choice.name == name) return value;
  throw std::logic_error("method " + choice.stage + "=" + choice.name + " is in the registry but not wired");
}

}  // namespace

bool names_classic_stage(const std::vector<MethodChoice>& choices) {
  for (const MethodChoice& choice : choices)
    if (choice.stage != "snap" && choice.stage != "tie_break") return true;
  return false;
}

ClassicMethods parse_classic_methods(const std::vector<MethodChoice>& choices) {
  ClassicMethods methods;
  std::vector<MethodChoice> setup_choices;
  for (const MethodChoice& choice : choices) {
    check_method_choice(choice);
    if (choice.stage == "snap" || choice.stage == "tie_break")
      setup_choices.push_back(choice);
    else if (choice.stage == "clip")
      methods.clip = lookup(choice, kClip);
    else if (choice.stage == "fill")
      methods.fill = lookup(choice, kFill);
    else if (choice.stage == "line")
      methods.line = lookup(choice, kLine);
    else if (choice.stage == "depth") {
      methods.depth = lookup(choice, kDepth);
      methods.pseudo_far = pseudo_depth_far(choice.name);
    } else if (choice.stage == "visibility")
      methods.visibility = lookup(choice, kVisibility);
    else if (choice.stage == "cull")
      methods.cull = lookup(choice, kCull);
  }
  methods.setup = parse_setup_methods(setup_choices);
  return methods;
}

}  // namespace rastercmp::cpu::classic
