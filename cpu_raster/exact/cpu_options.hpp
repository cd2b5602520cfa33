// What a caller asks of the CPU renderer: the profile, the FMA model, the thread count, the
// method overrides and the exact path's work skips. Every CPU layer reads it; the façade
// (cpu_raster/cpu_raster.hpp) picks the path from it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cpu_raster/exact/work_skips.hpp"
#include "model/lavapipe_release.hpp"
#include "model/scene.hpp"

namespace rastercmp {

enum class CpuProfile { Lavapipe, Spec };

struct CpuOptions {
  CpuProfile profile = CpuProfile::Lavapipe;
  // Model lavapipe's llvm.fmuladd as fused (true on FMA hosts; see lavapipe_fuses_on_this_host()).
  bool fma = true;
  // The lavapipe release the Lavapipe profile (and the spec profile's estimate) reproduces
  // (model/lavapipe_release.hpp). The oldest unless the caller picks one: the commands pick the
  // release of the driver they compare with (lavapipe_from_driver) or the one --profile names.
  const LavapipeRelease* lavapipe = &lavapipe_releases().front();
  // Whether a comparison replaces `lavapipe` by the release of the driver it compares with
  // (--profile lavapipe, compare/case_run.hpp), rather than keep it as forced (--profile lavapipe-X.Y).
  bool lavapipe_from_driver = true;
  // Sub-pixel precision of the device being judged (spec profile); lavapipe: 8.
  uint32_t sub_pixel_bits = 8;
  // Precision of the viewport's bounds on the device being judged (spec profile:
  // viewportSubPixelBits); lavapipe: 8.
  uint32_t viewport_sub_pixel_bits = 8;
  // 0: the exact scalar path alone. >= 1: the fast path with this many threads (bit-identical).
  uint32_t threads = 0;
  // The fast path: every one of `threads` workers even on a scene one worker would take alone
  // (a few thousand primitives), so that the soak's small scenes go through the phases that share
  // a frame between workers (rastercmp soak --every-worker). The bytes are the same either way.
  bool every_worker = false;
  // Method overrides (--method STAGE=NAME); empty: the exact pipeline.
  std::vector<MethodChoice> methods;
  // Measurement knob, exact path only (threads = 0): the work the scene's state makes unnecessary
  // is skipped (the default), or done anyway with identical output (docs/cpu-raster.md).
  cpu::WorkSkips skips;
};

// RenderResult::device of the Lavapipe profile: "cpu lavapipe-22.3.6 profile".
inline std::string lavapipe_profile_device(const CpuOptions& options) {
  return "cpu lavapipe-" + options.lavapipe->version.to_string() + " profile";
}

}  // namespace rastercmp
