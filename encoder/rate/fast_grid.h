// The fast profile's grid and low-rank model, both chosen by the fast file's own bytes: a
// grid ranked by another coder (format 3's, without a model) left a fast file 10-25 % larger
// than a grid its own low-rank model codes best on.
#pragma once
#include <cstdint>
#include <string>

#include "codec/common/model.h"
#include "encoder/io/frames.h"
#include "encoder/rate/fast_plan.h"
#include "encoder/rate/grid.h"

namespace dcurve {

// base: the file's metadata, faces and curves, no grid yet. refinement > 0: that grid, no
// trials; otherwise choose_grid's `search`, each trial a choose_fast_low_rank of the clip (or
// of its middle frames on large inputs). *out receives the whole clip's model: grid, low-rank
// model and fast payload.
bool choose_fast_grid(const Animation& anim, const Model& base, double max_distance, double refinement,
                      GridSearch search, const FastLayerOptions& options, Model* out, std::string* error);

// Frames the low-rank trials of choose_fast_grid are forecast to code (each trial codes its
// input's frames once), for an encode's progress: fixed_grid when refinement > 0.
uint64_t forecast_fast_grid_frames(const Animation& anim, bool fixed_grid, GridSearch search);

}  // namespace dcurve
