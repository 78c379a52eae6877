// Draco per frame: every frame its own Draco file (connectivity + positions), each with the
// smallest position quantization whose decoded max error meets the tolerance.
#pragma once
#include <vector>

#include "bench/baselines.h"

namespace dcurve::bench {

// Draco accepts 1..30 bits; below 8 is what large tolerances need (8 bits already gives
// about 3e-3 of L), above 24 float32 input has nothing left to keep.
constexpr int kDracoMinBits = 1, kDracoMaxBits = 24;

struct DracoPerFrameChoice {
  std::vector<int> bits;                 // per frame, in [kDracoMinBits, kDracoMaxBits]
  std::vector<std::vector<char>> files;  // per frame, the Draco file written with those bits
  std::vector<double> max_error;         // per frame, measured on the decoded file, fraction of L
  bool all_meet = false;                 // every frame within the tolerance
};

// Bisection over bits for all frames at once (one decode of every frame per round, so the
// per-frame errors come from measure_error with the animation's own L). A frame that no
// bit depth brings within the tolerance keeps kDracoMaxBits.
bool choose_draco_per_frame(const BenchContext& ctx, DracoPerFrameChoice* out, std::string* error);

}  // namespace dcurve::bench
