// The decoder's evaluation engine (format_spec/dcrv.md, "Evaluation"): tables built once at
// open, then each frame is a blend of two correction frames plus a few multiply-adds per
// vertex for the motion model. Internal to the decoder library.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

class FrameEvaluator {
 public:
  // Builds the tables for `model` (already validated) and its decoded grid positions `q`
  // (frame-major, empty when the file has no residual layer). Fails with a message when the
  // tables would exceed `max_floats` (the caller derives it from the file size) or when the
  // file uses a motion basis this build cannot evaluate.
  bool build(const Model& model, const std::vector<int32_t>& q, uint64_t max_floats, std::string* error);

  // Positions at frame coordinate x in [0, frame_count - 1] (x = t * (frame_count - 1)),
  // vertex_count * 3 floats into `out`. No allocation; const, so safe from many threads.
  void evaluate(double x, float* out) const;

  uint64_t table_floats() const { return corrections_.size() + weights_.size(); }

 private:
  // One curve's motions (its non-Zero axes) in one segment, with per-vertex weights: the
  // coefficients already contracted with the space functions at each vertex's u. Weights of
  // one vertex sit together (axis after axis, time_count each), so one pass over the curve
  // updates all three coordinates.
  struct CurveModel {
    uint32_t curve = 0;
    uint8_t axes = 0;  // active axes, 1..3
    uint8_t axis[3] = {0, 0, 0};
    Basis basis[3] = {Basis::Zero, Basis::Zero, Basis::Zero};
    uint8_t basis_case[3] = {0, 0, 0};
    double time_param[3] = {0, 0, 0};
    uint8_t time_count[3] = {0, 0, 0};
    uint8_t stride = 0;     // weights per vertex: sum of time_count
    size_t weights_at = 0;  // into weights_: curve length * stride floats
  };
  struct Span {
    uint32_t first = 0, last = 0;  // frames covered
    size_t corrections_at = 0;     // into corrections_: (last - first + 1) frames of V * 3
    size_t motions_begin = 0, motions_end = 0;
  };

  // out += sign * model(span, tau), tau in [0, 1]. The one place the model is evaluated:
  // corrections are built with sign = -1 through the same float operations, so at an input
  // frame the output is the grid position up to one rounding.
  void apply_model(const Span& span, double tau, float sign, float* out) const;

  uint32_t vertex_count_ = 0;
  uint32_t frame_count_ = 0;
  const Curves* curves_ = nullptr;
  std::vector<Span> spans_;
  std::vector<CurveModel> motions_;
  std::vector<float> weights_;
  std::vector<float> corrections_;
};

}  // namespace dcurve
