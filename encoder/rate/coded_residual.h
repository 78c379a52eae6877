// What the encoder knows of a residual payload it has just coded. Kept beside the Model, it
// lets later steps (the chunk length, block flags) recode the layer without decoding the
// payload to learn what the encoder computed.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/residual.h"

namespace dcurve {

struct CodedResidual {
  ResidualPlan plan;                // chunks, coding orders and predictors of the payload
  std::vector<int32_t> values;      // the grid values it codes, frame-major
  std::vector<int32_t> prediction;  // the Model predictor's values it subtracts; empty without
};

}  // namespace dcurve
