// The quantization grid that carries the error guarantee: every position rounded to it lies
// within tolerance * L of the input.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

// Grid step and origin for `anim` at max error `max_distance` (model units, > 0): the
// coarsest grid whose rounding stays within the bound (cube side 2 * max_distance /
// sqrt(3), less a margin for float32 output rounding) made `refinement` (>= 1) times finer,
// or the coarsest when the finer values would not fit an int32. The origin is the per-axis
// minimum over all frames, so grid values start at 0.
ResidualLayer make_grid(const Animation& anim, double max_distance, double refinement = 1.0);

// Bytes of `part` (frames of the animation) coded on `grid` by a trial encode, SIZE_MAX
// when it fails. `slot` (< kGridTrialSlots) names the grid tried, so the caller can keep
// that trial's result; `threads` is what the trial may use (0 = all cores).
constexpr size_t kGridTrialSlots = 7;
using GridTrial = std::function<size_t(const ResidualLayer& grid, const Animation& part, size_t slot, int threads)>;

struct GridChoice {
  ResidualLayer grid;
  size_t slot = 0;     // the trial that chose it
  bool whole = false;  // the trials coded the whole animation: that trial is the encode
};

// Frames each grid trial codes for an animation of `frames` x `vertices`: all of them up to
// a size, else a run from the middle (grid.cpp).
uint32_t grid_trial_frames(uint32_t frames, uint32_t vertices);

// How many times finer than the coarsest safe grid for `max_distance` a grid of `step` is.
double grid_refinement(double step, double max_distance);

// How widely choose_grid searches. Walk: from two refinements, then around the best while
// it moves (four trials for most inputs). Bracket: two refinements, one near each end of
// where the walk settles, side by side, and no more (grid.cpp says why these two).
enum class GridSearch { Walk, Bracket };

// The refinement an encode uses without any trial (effort 1 of EncodeOptions): of the
// single grids measured, the one whose worst loss against the walk's file was smallest
// (grid.cpp).
constexpr double kUntriedRefinement = 6.0;

// The coarsest grid or a finer one (grid.cpp lists them and says why), whichever codes
// `anim` (or, when it is large, a run of frames from its middle) smallest by `trial`, among
// the refinements `search` tries.
// threads: 0 = all cores; the choice never depends on it.
GridChoice choose_grid(const Animation& anim, double max_distance, int threads, const GridTrial& trial,
                       GridSearch search = GridSearch::Walk);

// Rounds every frame to the grid: q[(f * V + v) * 3 + axis]. Fails when a value would not fit
// an int32 (a tolerance far too small for the motion's range).
bool quantize_to_grid(const Animation& anim, const ResidualLayer& grid, std::vector<int32_t>* q,
                      std::string* error);

}  // namespace dcurve
