// Experiment scenes built in code (world space through model/camera.hpp, or window pixels through
// pixels_to_clip), so every sweep point is one function call away from its parameters.
#pragma once

#include <cstdint>
#include <string>

#include "experiments/coverage_model.hpp"
#include "model/scene.hpp"

namespace rastercmp::experiments {

// A scene where one draw (the "decal") is meant to win over the surface behind it.
struct DecalScene {
  Scene scene;
  uint32_t decal_draw = 1;
};

enum class PairKind { Coplanar, NearCoplanar, House, Identical };
const char* to_string(PairKind);

struct PairParams {
  PairKind kind = PairKind::Coplanar;
  DepthFormat format = DepthFormat::D16Unorm;
  double far_near_ratio = 1000;  // far fixed, near = far / ratio
  double angle_deg = 45;         // rotation of the plane away from facing the eye (depth slope)
  double separation = 0;         // NearCoplanar: world distance of the decal in front of the base
  DepthBias decal_bias;          // applied to the decal (negative factors pull it towards the eye)
  // Coplanar / NearCoplanar only: the far plane, the distance of the pair's centre from the eye and
  // a scale of its sides (the defaults give the pair described below).
  double far_plane = 100, distance = 50, scale = 1;
  // Coplanar / NearCoplanar only: the whole image moved by this many pixels (sub-pixel jitter).
  double jitter_x_px = 0, jitter_y_px = 0;
};

// How clip z is formed from the eye distance w with the camera's near n and far f (the cases of
// depth_far_near and fight_onset). Standard: z = f (w - n) / (f - n), compare Less, clear 1;
// reversed: z = n (f - w) / (f - n), compare Greater, clear 0. Float: as a float camera matrix
// forms it, fl(fl(A z_eye) + B) with A, B rounded to float; double: formed in double from w and
// rounded to float once. StandardFloat is the camera matrix's own z (model/camera.hpp).
enum class DepthMapping { StandardFloat, StandardDouble, ReversedFloat, ReversedDouble };
inline constexpr DepthMapping kDepthMappings[] = {DepthMapping::StandardFloat, DepthMapping::StandardDouble,
                                                   DepthMapping::ReversedFloat, DepthMapping::ReversedDouble};
// The case-name suffix: "", "_double_z", "_reversed_z_float", "_reversed_z".
const char* mapping_suffix(DepthMapping mapping);
const char* mapping_name(DepthMapping mapping);  // "standard, float z", ...
bool is_reversed(DepthMapping mapping);
// A case name's mapping (by its suffix) and the format name before the suffix.
DepthMapping case_depth_mapping(const std::string& case_name);
std::string case_depth_format(const std::string& case_name);
// Every clip z of the scene replaced as the mapping forms it (StandardFloat: unchanged).
Scene with_depth_mapping(Scene scene, DepthMapping mapping, double near_plane, double far_plane);

// The sub-pixel offset and depth phase of jitter j of an ensemble (j = 0: none): x and y offsets
// in pixels from the Halton sequences of bases 2 and 3, and a depth phase in [0, 1) from base 5
// (the caller scales it into a move away from the eye: stability.hpp kOnsetDepthPhaseRange).
struct Jitter {
  double x_px = 0, y_px = 0, depth_phase = 0;
};
Jitter ensemble_jitter(int j);

// Coplanar / near-coplanar pair: a 36x36 square 50 units in front of the eye (far = 100), split
// along one diagonal, drawn first; then a 24x20 decal on (or `separation` in front of) the same
// plane, split along the other diagonal, so the two interpolate depth from different vertices.
// Identical: one triangle of that square drawn twice with the same vertices (the polygon-offset
// control: the spec's r must separate the second draw, offset by 1 r, under compare op Less).
// House: the lecture's house (z 30..54, notes "clipping-fill-zbuffer"), camera of
// scenes/house/far_75.json (far 75), orbited by angle-45 degrees; decal = door and windows.
DecalScene make_decal_scene(const PairParams& params);

// The decal draw alone (for the mask of pixels where the decal should win).
Scene decal_only(const DecalScene& decal);

// A flat 48x48-pixel square at window depth kFlatPlaneDepth facing the eye (w = 1), one draw, with the bias.
inline constexpr float kFlatPlaneDepth = 0.375f;
Scene make_flat_plane(DepthFormat format, const DepthBias& bias);

// Two thin triangles sharing an edge through a pixel centre: apex angle `angle_deg`, edge length
// `length_px` pixels, in a 64x64 frame.
Scene make_sliver_pair(double angle_deg, double length_px);

// A long thin triangle reaching window x = distance_px (up to the viewportBoundsRange limit
// 32767): frame 16384 x 4, the viewport ending at the far vertex.
Scene make_far_triangle(double distance_px);
DesignTriangles far_triangle_design(double distance_px);  // its triangle, for the coverage model

// A height-field mesh of cells x cells quads (2 triangles each) seen in perspective, in a
// size x size frame with D32 depth: the timing scene with many small triangles.
Scene make_mesh_scene(uint32_t size, uint32_t cells);

// `lines` 1-pixel lines radiating from near the centre of a size x size frame, endpoints off the
// pixel grid, depth rising along each line: the timing scene of the line methods.
Scene make_line_star(uint32_t size, uint32_t lines);

// A triangle with one vertex at clip (0.2, 0.6, 0, w): on the near plane, w approaching 0.
Scene make_near_w_triangle(float w_clip);

// One vertex component (x, y, z or w: `component` 0..3) replaced by `value` (NaN, +Inf, -Inf).
Scene make_non_finite_triangle(uint32_t component, float value);

}  // namespace rastercmp::experiments
