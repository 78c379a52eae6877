// Rate control of the PDE motion model: which fitted motions (segment, curve, axis) the
// file keeps. A motion pays when the residual bits the Model predictor saves on its curve's
// vertices over its segment's frames exceed its stored bytes; the others become
// Basis::Zero (one byte each), and the residual layer codes those values without it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/rate/coded_residual.h"
#include "codec/common/residual.h"
#include "encoder/rate/encode_context.h"

namespace dcurve {

struct MotionChoiceOptions {
  // Residual plans whose estimates may drop motions, >= 0. Each plan after a drop sees the
  // remaining motions anew (neighbours of dropped ones may lose their use); one more plan,
  // which drops nothing, codes the payload.
  uint32_t max_screens = 2;
  // Keep every fitted motion whether it pays or not (in-betweens follow the model
  // everywhere; the file may get larger). For studies and tests.
  bool keep_all = false;
};

struct MotionChoiceReport {
  uint32_t fitted = 0;  // non-Zero motions before the choice
  uint32_t kept = 0;    // non-Zero motions in the result
  uint32_t plans = 0;   // residual plans made
  double estimated_saving = 0;  // residual bytes the kept motions are estimated to save
};

// Drops the motions of `model` that do not pay, and codes its residual payload.
//   model: curves, faces, grid (residual step and origin) and fitted segments; its payload
//     is replaced. When no motion pays, every motion becomes Zero and the payload is left
//     empty: the caller keeps `baseline`.
//   baseline: the finished encode of the same frames on the same grid without a PDE model
//     or a low-rank model, coding baseline_coded: the residual bits each value costs there
//     are what a motion has to beat.
//   context: the frames, their grid values and how to plan (its shared tables unused: the
//     model's own traversal is walked).
// coded (may be null): receives what the payload codes, when one is coded.
// Deterministic for any context.plan.threads. False only on an internal error.
bool choose_motions(Model* model, const Model& baseline, const CodedPayload& baseline_coded, const EncodeContext& context,
                    const MotionChoiceOptions& options, MotionChoiceReport* report, std::string* error,
                    CodedResidual* coded = nullptr);

}  // namespace dcurve
