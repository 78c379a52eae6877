// The residuals the residual layer codes, for measurements (codec/common/residual.h).
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"

namespace dcurve {

// The residuals encode_residuals would code, in coding order (frame in plan order,
// traversal position, axis): for measuring the entropy coder against general-purpose compressors.
// `plan` must be complete (from the encoder, or decode_predictor_plan with with_clusters);
// empty when it uses Motion without its maps.
std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                                     const ResidualOptions& options = {});
inline std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q,
                                            const PredictorPlan& plan, const ResidualOptions& options = {}) {
  return residual_values(model, q, single_chunk_plan(plan), options);
}

}  // namespace dcurve
