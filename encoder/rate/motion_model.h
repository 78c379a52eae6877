// The PDE motion model of a file: time segments and, per segment, curve and axis, a fitted
// closed-form motion (encoder/fit). It gives the decoder its in-between frames (x(t) follows
// the model between input frames) and the residual layer its "model" predictor.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

struct MotionModelOptions {
  Basis basis = Basis::Pde8;         // Pde8 or Pde32
  FitMode mode = FitMode::Absolute;  // Absolute or Displacement (from the rest pose)
  uint32_t segment_frames = 8;       // frames per segment step (>= 1); segments share end frames
  int threads = 0;                   // 0: all cores; the result never depends on it
  // Upper bound of mu (alpha) over a segment's unit time. Between input frames the decoder
  // follows the model, and with few frames per segment a large mu lets exponentials that
  // cancel at the frames swing far between them: a small bound keeps in-betweens smooth.
  double max_time_param = 3.0;
  // Largest change, model units, that rounding a motion's coefficients may make to it on
  // its curve's vertices and the segment's frames (> 0): the step of the stored integers
  // follows from it. The residual layer corrects the frames; in-betweens move this much.
  double coefficient_error = 1e-4;
};

// Frame boundaries of segments of about `segment_frames` steps tiling [0, frame_count - 1];
// the last segment absorbs the remainder so none is shorter than half a step.
std::vector<std::pair<uint32_t, uint32_t>> plan_segments(uint32_t frame_count, uint32_t segment_frames);

// Fits every curve of `curves` (u as the file will store it) on every segment of `anim`.
// `rest` is the decoder's frame 0 (Displacement mode only; V * 3 floats). On success
// `segments` tiles the frames with curve_count * 3 motions each.
bool fit_motion_model(const Animation& anim, const Curves& curves, const std::vector<float>& rest,
                      const MotionModelOptions& options, std::vector<Segment>* segments, std::string* error);

}  // namespace dcurve
