// The in-between rule a file records (format 3.2, Metadata::inbetween): the rule that best
// predicts held-out frames of the input. Within each segment the frames first, first + 2,
// ... stand for a clip at half the frame rate; each rule interpolates their corrections (the
// input minus the file's motion model) at the frames between, and the rule with the smallest
// squared error there wins. The rules cost no bytes, so the choice needs no trial encode.
#pragma once
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// Squared error, summed over vertices, axes and held-out frames, of each rule
// (index: Inbetween value), and how many held-out frames it covers.
struct InbetweenScores {
  double squared_error[kInbetweenCount] = {0, 0, 0};
  uint64_t held_out_frames = 0;
};

// Scores every rule on `frames` (vertex_count * 3 floats each) against *model's motion
// model (none: the frames themselves are interpolated). Fails only on a model whose tables
// do not build (an internal error).
bool score_inbetweens(const Model& model, const std::vector<std::vector<float>>& frames, InbetweenScores* scores,
                      std::string* error);

// Sets model->meta.inbetween: `forced` when it is a valid rule (0..kInbetweenCount - 1),
// else the best-scoring rule (Linear when no frame can be held out or rules tie).
bool choose_inbetween(Model* model, const std::vector<std::vector<float>>& frames, int forced, std::string* error);

}  // namespace dcurve
