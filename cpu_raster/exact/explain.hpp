// Why a sample ended up as it did on the CPU exact path (lavapipe profile): one record per
// primitive that reached the pixel (its bounding box or the pixels its rasterizer visits) or
// covered the sample, in submission order, with the values of every stage. It runs the exact
// path's own stage functions (front end, edge planes, sample evaluation, depth test) and replays
// the depth test of this one sample, so "stored before/after" are what the render holds.
// The spec profile's owner/depth estimate is the lavapipe render, so both profiles trace it.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "cpu_raster/exact/cpu_options.hpp"
#include "model/render_result.hpp"
#include "model/scene.hpp"

namespace rastercmp {

// Why a primitive that reached the pixel did not get through set-up.
enum class CullReason {
  None,           // set-up passed
  Facing,         // its face is culled (fixed-point area sign, docs/lavapipe-rules.md §2.3)
  Degenerate,     // zero fixed-point area, or a zero-length line
  FloatCull,      // the draw pipeline's float cull after clipping (§2.6)
  OutsideRegion,  // its bounding box misses framebuffer ∩ scissor ∩ viewport (§2.5)
  NonFinite,      // a coordinate that does not snap (NaN, Inf, beyond the 24.8 bound)
};

// Why a primitive through set-up did not cover the sample.
enum class MissReason {
  None,        // covered
  Edge,        // edge plane `failing_plane` has E <= 0 at the sample
  Scissor,     // scissor/region plane `failing_plane - edge_count` excludes the sample
  NotVisited,  // every plane includes it, but lavapipe's rasterizer never visits the pixel
};

struct FragmentRecord {
  uint32_t draw_index = 0;
  uint32_t primitive_index = 0;
  bool is_line = false;

  bool clipped = false;      // the clipper cut this primitive
  uint32_t clip_piece = 0;   // which triangle of the clipped fan this record is
  uint32_t clip_pieces = 1;  // how many triangles (or lines) the clipper produced

  CullReason cull = CullReason::None;
  bool front_facing = false;
  int64_t fixed_area = 0;  // doubled signed area in 1/256 px units (triangles, before the swap)
  bool float_cull_ran = false;
  float float_det = 0;  // draw_pipe_cull.c determinant when the float cull ran

  // Set-up passed: the planes at the sample, in 24.8 fixed point.
  int64_t sample_x_fixed = 0, sample_y_fixed = 0;  // the sample in the snapped frame
  uint32_t edge_count = 0;                         // 3 or 4 (line quad)
  std::array<int64_t, 4> edge_value{};             // E_i, including the +1 of inclusive edges
  std::array<bool, 4> edge_inclusive{};            // got the top-left +1
  uint32_t scissor_plane_count = 0;
  std::array<int64_t, 4> scissor_value{};
  bool covered = false;
  MissReason miss = MissReason::None;
  int failing_plane = -1;

  // Depth (covered samples of draws with an active depth test).
  bool depth_tested = false;
  float depth_interpolated = 0;  // before the bias
  bool bias_computed = false;
  float bias_m = 0, bias_r = 0;  // max slope and the resolvable difference r
  float bias_constant_factor = 0, bias_slope_factor = 0, bias_clamp = 0;
  bool bias_clamp_applied = false;
  float bias_offset = 0;  // o
  float depth_with_offset = 0;
  float depth_clamped_01 = 0;
  bool depth_clamp_enabled = false;
  float depth_clamped = 0;  // after the depth clamp (equal when it is off)
  uint32_t depth_raw = 0;   // what the attachment would store
  CompareOp compare_op = CompareOp::Always;
  uint32_t depth_sample = 0;            // whose stored depth is tested and written
  bool one_fragment_per_pixel = false;  // not multisampled in a 4x framebuffer: sample 0 tested, owner to all (§6)
  uint32_t stored_before = 0;
  bool depth_passed = false;
  uint32_t stored_after = 0;

  bool owner_written = false;  // this primitive's id is the sample's owner after it
};

// Throws NotSupportedError (state the profile cannot reproduce), UsageError (a pixel or sample
// outside the framebuffer, a bad method), InputError (a scene the model cannot take).
std::vector<FragmentRecord> explain_pixel(const Scene& scene, const CpuOptions& options, uint32_t x, uint32_t y,
                                          uint32_t sample = 0);

// A table, one row per record, with bias and clamp details under the rows that have them.
std::string format_explanation(const std::vector<FragmentRecord>& records);

}  // namespace rastercmp
