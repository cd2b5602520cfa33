// "Work skips" of the exact path: the work a scene's state makes unnecessary, each skip on by
// default. Turning one off is a measurement knob (bench/bench_skips.cpp): the exact path then does
// that work anyway, in a way that leaves every owner id and every depth bit unchanged
// (tests/test_work_skips.cpp). docs/cpu-raster.md "What each skip buys".
#pragma once

namespace rastercmp::cpu {

struct WorkSkips {
  // Clip only primitives with a vertex outside a plane (the union of the clip masks is non-zero,
  // docs/lavapipe-rules.md §1.5). Off: primitives wholly inside also run through the clipper, against every
  // plane the clip test uses; the clipper hands them back unchanged.
  bool clip_only_when_needed = true;
  // Depth set-up and per-sample depth only with a depth attachment and the test on. Off: the depth
  // plane, the polygon offset and every covered sample's depth are computed anyway and discarded.
  bool depth_only_when_attached = true;
  // Polygon-offset arithmetic only when the bias is on with a non-zero factor (§4.3). Off: the
  // offset terms are formed with zero factors and discarded; the offset stays exactly 0.
  bool bias_only_when_enabled = true;
  // 32-bit edge values where the primitive's pixel box allows it (edge_frame32.hpp). Off: 64-bit
  // edge values for every primitive.
  bool edges32_when_box_fits = true;
};

}  // namespace rastercmp::cpu
