// Rate control of the low-rank model: whether the file carries one (LRNK) for the residual
// layer's Model predictor, with how many components and how coarse, judged by whole-file
// bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/container.h"
#include "codec/model.h"

namespace dcurve {

struct LowRankChoiceOptions {
  // -1: automatic (kept only when the file gets smaller); 0: never; K in 1..64: always use K
  // components (for studies; the file may get larger).
  int components = -1;
  // Full residual encodes tried with a low-rank model, best screened candidates first (one
  // per component count), >= 1; max_cheap_trials on inputs of at most 2^18 vertex-frames.
  // The screening misjudges savings by up to 2x both ways, so its first choice can fail its
  // trial while another count pays: blob at 1e-3 (grid 3x) screened K = 8 first, whose trial
  // lost, and K = 16 second.
  uint32_t max_trials = 1, max_cheap_trials = 2;
  int threads = 0;  // 0: all cores; the result never depends on it
};

struct LowRankChoiceReport {
  uint32_t components = 0;       // K of the model kept, 0 when none
  double basis_step = 0;         // grid units
  uint32_t screened = 0, trials = 0;
  uint64_t bytes_without = 0;    // the whole file without a low-rank model
  uint64_t bytes = 0;            // the whole file kept (bytes_without when it has no model)
};

// `model` holds a finished encode without a low-rank model (residual payload coded, no PDE
// motions); `rounded` is the grid values before snapping (frame-major), `frames` the input
// (model units) and `snap_distance` how far snapping may move a value (model units). Screens
// low-rank models by a cheap estimate, encodes the residual with the promising ones and keeps
// the smallest whole file in `model` (low_rank and residual.payload replaced). False only on
// an internal error.
bool choose_low_rank(Model* model, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
                     double snap_distance, const WriteOptions& write_options, const LowRankChoiceOptions& options,
                     LowRankChoiceReport* report, std::string* error);

}  // namespace dcurve
