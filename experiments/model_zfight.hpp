// `rastercmp sweep zfight --model MODEL`: z-fighting on real content. The model is imported with
// its framing camera (model/mesh_import.hpp); far stays the framing camera's (it holds the
// bounding sphere) and near is far / R for a series of far/near ratios R. Clip z is recomputed in
// double from the eye distance w for both mappings, so standard and reversed Z differ only in the
// mapping:
//   standard  z_ndc = f (d - n) / (d (f - n)), LESS, clear 1;
//   reversed  z_ndc = n (f - d) / (d (f - n)), GREATER, clear 0.
// For every depth format, mapping and R, the model is rendered at a few sub-pixel jitters of the
// view (a clip-space shift of x and y) and each render is compared with the reference at the same
// jitter (D32, reversed, the framing camera's near: the most precise depth there is); the fraction
// is the share of covered pixels whose owner differs, so only depth precision can move it.
//
// The prediction: a depth step of the buffer is an eye-distance step at distance d of
//   integer, B bits, either mapping   dd = d^2 (R - 1) / (f (2^B - 1))
//   D32 standard                      dd = ulp(z) d^2 (R - 1) / f, ulp(z) = 2^-24 where z is in [0.5, 1)
//   D32 reversed                      dd ~ d 2^-23, whatever R (no onset)
// and surfaces fight once dd exceeds the gap g between a visible surface and the one behind it.
// g is the model's: it is calibrated from the measured onset of D16 standard (the first R where the
// fraction passes kOnsetFraction), and the other series' onsets are predicted from it:
// R* = 1 + g f (2^B - 1) / d^2 (d: the target distance), D32 standard as B = 24, D32 reversed none.
#pragma once

#include <string>

#include "experiments/sweep_common.hpp"

namespace rastercmp::experiments {

inline constexpr double kOnsetFraction = 1e-3;  // a fraction above this is a fight

struct ModelZfightOptions {
  SweepOptions sweep;
  std::string model;
  uint32_t width = 512, height = 512;
};

// Writes zfight.csv, zfight.json (the measured onset bracket and the prediction per series),
// zfight_far_near.svg/png and index.html into sweep.out_dir.
void run_model_zfight_sweep(const ModelZfightOptions& options);

}  // namespace rastercmp::experiments
