#include "cpu_raster/classic/classic_methods.hpp"

#include <array>
#include <string>
#include <string_view>
#include <utility>

#include "model/errors.hpp"

namespace rastercmp::cpu::classic {
namespace {

template <class Enum, size_t N>
using NameTable = std::array<std::pair<std::string_view, Enum>, N>;

constexpr NameTable<ClipMethod, 4> kClip{{{"exact", ClipMethod::Exact},
                                          {"sutherland_hodgman", ClipMethod::SutherlandHodgman},
                                          {"cohen_sutherland_3d", ClipMethod::CohenSutherland3d},
                                          {"liang_barsky", ClipMethod::LiangBarsky}}};
constexpr NameTable<FillMethod, 5> kFill{{{"exact", FillMethod::Exact},
                                          {"scanline", FillMethod::Scanline},
                                          {"float_edge", FillMethod::FloatEdge},
                                          {"even_odd", FillMethod::EvenOdd},
                                          {"winding", FillMethod::Winding}}};
constexpr NameTable<LineMethod, 3> kLine{
    {{"exact", LineMethod::Exact}, {"dda", LineMethod::Dda}, {"bresenham", LineMethod::Bresenham}}};
constexpr NameTable<DepthMethod, 4> kDepth{{{"exact", DepthMethod::Exact},
                                            {"no_fma", DepthMethod::NoFma},
                                            {"bilinear", DepthMethod::Bilinear},
                                            {"perspective_correct", DepthMethod::PerspectiveCorrect}}};
constexpr NameTable<VisibilityMethod, 3> kVisibility{
    {{"zbuffer", VisibilityMethod::ZBuffer}, {"painter", VisibilityMethod::Painter}, {"bsp", VisibilityMethod::Bsp}}};
constexpr NameTable<CullMethod, 2> kCull{
    {{"exact", CullMethod::Exact}, {"normal_dot_view", CullMethod::NormalDotView}}};

constexpr std::string_view kClassicStages = "clip, fill, line, depth, visibility, cull";

template <class Enum, size_t N>
Enum lookup(const MethodChoice& choice, const NameTable<Enum, N>& table) {
  std::string known;
  for (const auto& [name, value] : table) {
    if (choice.name == name) return value;
    known += (known.empty() ? "" : ", ") + std::string(name);
  }
  throw UsageError("method " + choice.stage + "=" + choice.name + ": unknown name for stage \"" + choice.stage +
                   "\"; known: " + known);
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
    if (choice.stage == "snap" || choice.stage == "tie_break")
      setup_choices.push_back(choice);
    else if (choice.stage == "clip")
      methods.clip = lookup(choice, kClip);
    else if (choice.stage == "fill")
      methods.fill = lookup(choice, kFill);
    else if (choice.stage == "line")
      methods.line = lookup(choice, kLine);
    else if (choice.stage == "depth")
      methods.depth = lookup(choice, kDepth);
    else if (choice.stage == "visibility")
      methods.visibility = lookup(choice, kVisibility);
    else if (choice.stage == "cull")
      methods.cull = lookup(choice, kCull);
    else
      throw UsageError("method " + choice.stage + "=" + choice.name + ": unknown stage \"" + choice.stage +
                       "\"; known stages: " + std::string(kClassicStages) + ", snap, tie_break");
  }
  methods.setup = parse_setup_methods(setup_choices);
  return methods;
}

}  // namespace rastercmp::cpu::classic
