// Encoder-side choice of the residual predictors: for every frame and axis, the predictor
// (codec/predictors.h) whose residuals are estimated to cost the fewest bits.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/model.h"
#include "codec/residual.h"

namespace dcurve {

struct ResidualPlanOptions {
  // Past frames tried as a reference besides the previous two, picked by the smallest
  // difference to the frame being coded (animations repeat their poses). >= 0.
  uint32_t extra_references = 3;
  // How far back reference frames are searched, frames, >= 1.
  uint32_t max_reference_distance = 1024;
};

// Estimated cost, bits, of coding `residuals` with an adaptive integer coder: their
// order-0 entropy over exponent classes plus the raw mantissa bits. Used to rank
// predictors, not to predict file sizes exactly.
double estimate_residual_bits(const std::vector<int64_t>& residuals);

// Picks the plan for model (counts, faces, curves as encode_residuals will see them) and
// grid values q (frame-major). Deterministic; cost O(F * candidates * (V + edges)).
PredictorPlan choose_predictor_plan(const Model& model, const std::vector<int32_t>& q,
                                    const ResidualOptions& options = {},
                                    const ResidualPlanOptions& plan_options = {});

}  // namespace dcurve
