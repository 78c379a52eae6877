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

// A seek (a fresh cursor, any frame) decodes at most this many frames: the decoder starts at
// the last frame at or before it that reads no earlier one (Model or None, and every chunk's
// first frame), and the planner picks such a kind wherever a seek would otherwise decode more.
constexpr uint32_t kMaxSeekFrames = 4;

// The chunk lengths the encoder considers for F frames: 4, 8, ... up to a tenth of the clip
// (at least 4, at most 64), so a seek reads at most about a tenth of the clip's streams.
std::vector<uint32_t> fast_chunk_candidates(uint32_t F);

// The most frames a seek decodes into F frames of these kinds in chunks of K.
uint32_t fast_seek_frames(const std::vector<uint8_t>& kinds, uint32_t K);

}  // namespace dcurve
