// What every rate-control step of one encode reads, built once by encoder.cpp: the input,
// its grid values and how far snapping may move them, what every residual walk shares, and
// how to plan and write the file.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/predictors.h"
#include "codec/compress/container_writer.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {

struct EncodeContext {
  EncodeContext(const std::vector<std::vector<float>>& input, const std::vector<int32_t>& values)
      : frames(input), rounded(values) {}

  const std::vector<std::vector<float>>& frames;  // input positions, model units
  const std::vector<int32_t>& rounded;             // grid values before snapping, frame-major
  double snap_distance = 0;                        // how far snapping may move a value, model units
  // The spatial weight tables and the traversal every walk shares (either may be null: then
  // built where needed; results never depend on them). No model prediction here.
  ResidualOptions shared;
  ResidualPlanOptions plan;  // the planner's options and threads (0: all cores)
  WriteOptions write;
};

}  // namespace dcurve
