// The fast profile's residual layer (format 4, format_spec/residual.md section 10): per
// frame the predictor whose residuals cost least, the grid values snapped against it inside
// the tolerance ball, and the chunk length that codes smallest among those short enough for
// cheap random access.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

class WorkMeter;

struct FastLayerOptions {
  double snap_distance = 0;  // how far a grid value may sit from the input, model units
  uint32_t chunk_frames = 0;  // 0: chosen here
  int threads = 0;            // 0: all cores
  // choose_fast_low_rank's component count: -1 searched, 0 none, else that many (at most
  // what the frames have).
  int components = -1;
  WorkMeter* meter = nullptr;  // counts the frames of every low-rank trial; may be null
};

// Replaces m's residual payload (its grid step and origin kept, its Model prediction, LRNK
// or PDE, used when it has one) by a fast payload of the input frames. prediction (may be
// null): that Model prediction (frame-major grid values) when the caller has it, as an
// encoder has from the values its basis payload codes; else computed from m.
bool encode_fast_layer(Model* m, const std::vector<std::vector<float>>& frames, const FastLayerOptions& options,
                       std::string* error, const std::vector<int32_t>* prediction = nullptr);

// The chunk lengths the encoder considers for F frames: short enough that one frame costs at
// most about a tenth of the clip to reach, and at least 4.
std::vector<uint32_t> fast_chunk_candidates(uint32_t F);

}  // namespace dcurve
