// The decoder's evaluation engine (format_spec/dcrv.md, "Evaluation"): the motion model's
// per-vertex weights, built once at open, and the blend of two decoded frames' corrections
// plus a few multiply-adds per vertex for the model. The decoder evaluates with it, and
// GridPredictor (codec/decompress/model_prediction.h) evaluates the PDE model with it for
// encoder and decoder alike.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

class FrameEvaluator {
 public:
  // Where frame coordinate x falls: the segment used, the frames i and i + 1 blended with
  // weight w on i + 1 (w = 0: frame i alone), and the segment's local time tau.
  struct Place {
    size_t span = 0;
    uint32_t i = 0;
    float w = 0.f;
    double tau = 0.0;
  };

  // Builds the model tables of `model` (already validated). Fails with a message when the
  // tables would exceed `max_floats` (the caller derives it from the file size) or when the
  // file uses a motion basis this build cannot evaluate.
  bool build(const Model& model, uint64_t max_floats, std::string* error);

  // The place of x, clamped to [0, frame_count - 1] (NaN maps to 0).
  Place locate(double x) const;
  bool has_model() const { return !motions_.empty(); }

  // The motion model alone at `place`: vertex_count * 3 floats into out.
  void model_at(const Place& place, float* out) const;

  // Positions at `place` from the grid values of frames i and i + 1 (next may be null when
  // w = 0): the model plus the blended corrections. scratch: 3 * vertex_count floats when
  // has_model(). No allocation; const, so safe from many threads.
  void evaluate(const Place& place, const ResidualLayer& grid, const int32_t* frame, const int32_t* next,
                float* scratch, float* out) const;

  // Frame f's correction in the segment of `place` (D(f) = X_f - M(f) in binary32, from its
  // grid values q) into d: what evaluate_weighted sums. It depends on the frame and the
  // segment only, so a caller may keep it for the in-betweens around f.
  void frame_correction(const Place& place, const ResidualLayer& grid, const int32_t* q, uint32_t f, float* d) const {
    corrections(spans_[place.span], grid, q, f, d);
  }
  // Positions at `place` by a cubic in-between rule: the model plus the weighted sum of the
  // corrections of frames i - 2 .. i + 3 (corrections[k], frame_correction of frame
  // i - 2 + k, and weight[k], codec/common/inbetween.h; a frame of weight 0 may be null).
  void evaluate_weighted(const Place& place, const float* const* corrections, const double* weight, float* out) const;
  // The frames [first, last] of the segment `place` falls in.
  uint32_t span_first(const Place& place) const { return spans_[place.span].first; }
  uint32_t span_last(const Place& place) const { return spans_[place.span].last; }

  size_t memory_bytes() const {
    return weights_.capacity() * sizeof(float) + motions_.capacity() * sizeof(CurveModel) +
           spans_.capacity() * sizeof(Span);
  }

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
    size_t motions_begin = 0, motions_end = 0;
  };

  bool build_span_motions(const Model& m, const Segment& s, size_t* weights_at, std::string* error);
  // out += sign * model(span, tau), tau in [0, 1]. The one place the model is evaluated.
  void apply_model(const Span& span, double tau, float sign, float* out) const;
  double tau_of(const Span& span, double x) const;
  // D(f) = X_f - M(f) in binary32 into d: the correction the model's output is added to.
  void corrections(const Span& span, const ResidualLayer& grid, const int32_t* q, uint32_t f, float* d) const;

  uint32_t vertex_count_ = 0;
  uint32_t frame_count_ = 0;
  const Curves* curves_ = nullptr;
  std::vector<Span> spans_;
  std::vector<CurveModel> motions_;
  std::vector<float> weights_;
};

}  // namespace dcurve
