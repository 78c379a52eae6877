// Rate control of the PDE motion model's shape: among motion sets fitted with different
// segment lengths and basis sets, the segmentation and, per motion (segment, curve, axis),
// the basis set estimated to make the smallest file. Screening only: which of the chosen
// motions pay is then decided by the residual plan (motion_choice.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/rate/coded_residual.h"

namespace dcurve {

struct MotionAlternativesReport {
  size_t segmentation = 0;       // index into the alternatives of the chosen segmentation's first set
  double estimated_bytes = 0;    // its estimate: residual bytes of the values plus motion bytes
  double baseline_bytes = 0;     // the baseline's residual bytes of the same values
  uint32_t motions = 0;          // non-Zero motions chosen
  // Of them, those whose estimate is near enough the baseline's bytes that a residual plan
  // may find them paying; 0: no plan needs to be tried.
  uint32_t promising = 0;
};

// Chooses among `fitted` (each a segment list tiling the frames for model.curves, as from
// fit_motion_model; lists with identical segment bounds form one segmentation) and writes
// the chosen segments to `chosen`.
//   model: curves, faces and grid (its segments are ignored).
//   baseline: the finished encode without a PDE model on the same grid, coding
//     baseline_coded; its per-value residual bits are what a motion must beat.
//   rounded: grid values of the input frames (frame-major).
// A motion's estimate is its SEGS bytes plus the residual bytes of its values under the
// Model predictor alone (per frame the cheaper of no spatial correction and the mean of the
// earlier neighbours' errors), priced with the baseline's residual statistics; a
// segmentation's estimate sums, over its motion slots, the cheaper of the best basis's
// estimate and the baseline's bytes. The smallest wins, the earliest on ties. Deterministic.
bool choose_motion_alternative(const Model& model, const Model& baseline, const CodedPayload& baseline_coded,
                               const std::vector<std::vector<Segment>>& fitted, const std::vector<int32_t>& rounded,
                               std::vector<Segment>* chosen, MotionAlternativesReport* report, std::string* error);

}  // namespace dcurve
