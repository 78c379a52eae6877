// What the encoder knows of the residual payloads it has just coded. Kept beside the Model,
// it lets later steps (the chunk length, block flags, the fast basis) recode a layer without
// decoding the payload to learn what the encoder computed.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/residual.h"

namespace dcurve {

// One payload of the residual coder: the plan it followed and the grid values it codes,
// frame-major (for a low-rank basis: the mean, then the basis vectors).
struct CodedPayload {
  ResidualPlan plan;
  std::vector<int32_t> values;
};

struct CodedResidual {
  CodedPayload resi;                // the frames (RESI)
  std::vector<int32_t> prediction;  // the Model predictor's values RESI subtracts; empty without
  CodedPayload basis;               // the low-rank mean and basis (LRNK); empty without
};

}  // namespace dcurve
