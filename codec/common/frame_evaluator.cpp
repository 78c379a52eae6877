#include "codec/common/frame_evaluator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "codec/common/basis.h"
#include "codec/common/error.h"
#include "codec/common/inbetween.h"
#include "codec/common/residual.h"

namespace dcurve {
namespace {
// double -> float, saturating to +-inf instead of the undefined conversion of an
// out-of-range value (the finiteness checks after building then reject the file).
float to_float(double v) {
  if (v > double(std::numeric_limits<float>::max())) return std::numeric_limits<float>::infinity();
  if (v < -double(std::numeric_limits<float>::max())) return -std::numeric_limits<float>::infinity();
  return float(v);
}
constexpr int kMaxTimeTerms = 4;
constexpr int kMaxSpaceTerms = 8;
}  // namespace

bool FrameEvaluator::build(const Model& m, uint64_t max_floats, std::string* error) {
  vertex_count_ = m.meta.vertex_count;
  frame_count_ = m.meta.frame_count;
  curves_ = &m.curves;

  // A file without segments is one span with no model: plain interpolation of the frames.
  std::vector<Segment> implicit;
  const std::vector<Segment>* segments = &m.segments;
  if (m.segments.empty()) {
    implicit.resize(1);
    implicit[0].last_frame = frame_count_ - 1;
    segments = &implicit;
  }

  // Count first, allocate after: the tables never exceed the caller's bound.
  uint64_t weight_floats = 0;
  for (const Segment& s : *segments) {
    for (size_t k = 0; k < s.motion.size(); ++k) {
      const CurveMotion& cm = s.motion[k];
      if (cm.basis == Basis::Zero) continue;
      uint32_t c = uint32_t(k / 3);
      weight_floats += uint64_t(m.curves.offsets[c + 1] - m.curves.offsets[c]) * basis_time_count(cm.basis);
    }
    if (weight_floats > max_floats)
      return fail(error, "model tables would need " + std::to_string(weight_floats) +
                             "+ floats, implausible for the file size");
  }

  spans_.clear();
  motions_.clear();
  weights_.assign(size_t(weight_floats), 0.f);
  size_t weights_at = 0;
  for (const Segment& s : *segments) {
    Span span;
    span.first = s.first_frame;
    span.last = s.last_frame;
    span.motions_begin = motions_.size();
    if (!build_span_motions(m, s, &weights_at, error)) return false;
    span.motions_end = motions_.size();
    spans_.push_back(span);
  }
  for (float w : weights_)
    if (!std::isfinite(w)) return fail(error, "motion model overflows at some vertex");
  return true;
}

bool FrameEvaluator::build_span_motions(const Model& m, const Segment& s, size_t* weights_at, std::string* error) {
  for (uint32_t c = 0; c < s.motion.size() / 3; ++c) {
    CurveModel cmod;
    cmod.curve = c;
    for (uint8_t a = 0; a < 3; ++a) {
      const CurveMotion& cm = s.motion[size_t(c) * 3 + a];
      if (cm.basis == Basis::Zero) continue;
      const int tc = basis_time_count(cm.basis), sc = basis_space_count(cm.basis);
      if (tc > kMaxTimeTerms || sc > kMaxSpaceTerms || cm.coeffs.size() != size_t(tc) * sc)
        return fail(error, "motion basis term counts do not match the coefficients");
      const uint8_t k = cmod.axes++;
      cmod.axis[k] = a;
      cmod.basis[k] = cm.basis;
      cmod.basis_case[k] = cm.basis_case;
      cmod.time_param[k] = cm.time_param;
      cmod.time_count[k] = uint8_t(tc);
      cmod.stride = uint8_t(cmod.stride + tc);
    }
    if (cmod.axes == 0) continue;
    cmod.weights_at = *weights_at;
    const uint32_t begin = m.curves.offsets[c], end = m.curves.offsets[c + 1];
    for (uint32_t j = begin; j < end; ++j)
      for (uint8_t k = 0; k < cmod.axes; ++k) {
        const CurveMotion& cm = s.motion[size_t(c) * 3 + cmod.axis[k]];
        const int tc = cmod.time_count[k], sc = basis_space_count(cm.basis);
        double space[kMaxSpaceTerms];
        basis_space(cm.basis, cm.basis_case, cm.space_param, m.curves.u[j], space);
        for (int it = 0; it < tc; ++it) {
          double acc = 0;
          for (int is = 0; is < sc; ++is) acc += double(cm.coeffs[size_t(it) * sc + is]) * space[is];
          weights_[(*weights_at)++] = to_float(acc);
        }
      }
    motions_.push_back(cmod);
  }
  return true;
}

namespace {
struct TimeKey {
  Basis basis = Basis::Zero;
  uint8_t basis_case = 0;
  double param = 0;
  bool operator==(const TimeKey& o) const { return basis == o.basis && basis_case == o.basis_case && param == o.param; }
};
constexpr int kTimeCache = 3;

// The per-vertex kernel for the common case, every axis of the curve on a basis with TC time
// functions: fixed trip counts let the compiler unroll it to 3 * TC multiply-adds.
template <int TC>
void add_curve3(const float (*time)[kMaxTimeTerms], const float* w, const uint32_t* ids, uint32_t n, float sign,
                float* out) {
  for (uint32_t j = 0; j < n; ++j, w += 3 * TC) {
    float* o = out + size_t(ids[j]) * 3;
    for (int a = 0; a < 3; ++a) {
      float sum = 0.f;
      for (int i = 0; i < TC; ++i) sum += time[a][i] * w[a * TC + i];
      o[a] += sign * sum;
    }
  }
}
}  // namespace

void FrameEvaluator::apply_model(const Span& span, double tau, float sign, float* out) const {
  TimeKey cache_key[kTimeCache];
  float cache_time[kTimeCache][kMaxTimeTerms];
  int cached = 0, next_slot = 0;
  for (size_t k = span.motions_begin; k < span.motions_end; ++k) {
    const CurveModel& cm = motions_[k];
    float time[3][kMaxTimeTerms];
    for (int a = 0; a < cm.axes; ++a) {
      // The time functions cost far more than a curve's multiply-adds: reuse them when the
      // previous curve or another axis has the same basis, case and parameter.
      const TimeKey key{cm.basis[a], cm.basis_case[a], cm.time_param[a]};
      int hit = -1;
      for (int c = 0; c < cached && hit < 0; ++c)
        if (cache_key[c] == key) hit = c;
      if (hit < 0) {
        double t[kMaxTimeTerms] = {0, 0, 0, 0};
        basis_time(key.basis, key.basis_case, key.param, tau, t);
        hit = next_slot;
        next_slot = (next_slot + 1) % kTimeCache;
        cached = std::min(cached + 1, kTimeCache);
        cache_key[hit] = key;
        for (int i = 0; i < kMaxTimeTerms; ++i) cache_time[hit][i] = to_float(t[i]);
      }
      std::copy_n(cache_time[hit], kMaxTimeTerms, time[a]);
    }
    const uint32_t begin = curves_->offsets[cm.curve], end = curves_->offsets[cm.curve + 1];
    const uint32_t* ids = curves_->vertices.data() + begin;
    const float* w = weights_.data() + cm.weights_at;
    if (cm.axes == 3 && cm.stride == 6) {
      add_curve3<2>(time, w, ids, end - begin, sign, out);
    } else if (cm.axes == 3 && cm.stride == 12) {
      add_curve3<4>(time, w, ids, end - begin, sign, out);
    } else {
      // Mixed bases or Zero axes: the same sums with run-time trip counts.
      for (uint32_t j = 0; j < end - begin; ++j) {
        float* o = out + size_t(ids[j]) * 3;
        for (int a = 0; a < cm.axes; ++a) {
          float sum = 0.f;
          for (int i = 0; i < cm.time_count[a]; ++i) sum += time[a][i] * *w++;
          o[cm.axis[a]] += sign * sum;
        }
      }
    }
  }
}

double FrameEvaluator::tau_of(const Span& span, double x) const {
  const uint32_t len = span.last - span.first;
  return len ? (x - span.first) / len : 0.0;
}

FrameEvaluator::Place FrameEvaluator::locate(double x) const {
  const double last_x = double(frame_count_ - 1);
  if (!(x > 0.0)) x = 0.0;  // also catches NaN
  if (x > last_x) x = last_x;
  // The span with the largest first frame <= x: on a shared boundary frame the later wins.
  auto it = std::upper_bound(spans_.begin(), spans_.end(), x,
                             [](double v, const Span& s) { return v < double(s.first); });
  const Span& span = *(it - 1);
  Place p;
  p.span = size_t(it - 1 - spans_.begin());
  p.i = span.first;
  if (span.last > span.first) {
    p.i = std::min(uint32_t(x), span.last - 1);
    p.w = float(x - double(p.i));
  }
  p.tau = tau_of(span, x);
  return p;
}

void FrameEvaluator::model_at(const Place& place, float* out) const {
  std::fill_n(out, size_t(vertex_count_) * 3, 0.f);
  const Span& span = spans_[place.span];
  if (span.motions_end > span.motions_begin) apply_model(span, place.tau, 1.f, out);
}

void FrameEvaluator::corrections(const Span& span, const ResidualLayer& grid, const int32_t* q, uint32_t f,
                                 float* d) const {
  const size_t V = vertex_count_;
  for (size_t v = 0; v < V; ++v)
    for (int a = 0; a < 3; ++a) d[v * 3 + size_t(a)] = grid_to_model(grid, a, q[v * 3 + size_t(a)]);
  if (span.motions_end > span.motions_begin) apply_model(span, tau_of(span, double(f)), -1.f, d);
}

void FrameEvaluator::evaluate(const Place& place, const ResidualLayer& grid, const int32_t* frame, const int32_t* next,
                              float* scratch, float* out) const {
  const size_t V = vertex_count_;
  const Span& span = spans_[place.span];
  const bool blend = place.w != 0.f && next;
  const bool model = span.motions_end > span.motions_begin;
  if (!model && !blend) {
    for (size_t v = 0; v < V; ++v)
      for (int a = 0; a < 3; ++a) out[v * 3 + size_t(a)] = grid_to_model(grid, a, frame[v * 3 + size_t(a)]);
    return;
  }
  corrections(span, grid, frame, place.i, out);
  if (blend) {
    corrections(span, grid, next, place.i + 1, scratch);
    const float w = place.w;
    for (size_t k = 0; k < V * 3; ++k) out[k] = out[k] + w * (scratch[k] - out[k]);
  }
  if (model) apply_model(span, place.tau, 1.f, out);
}

void FrameEvaluator::evaluate_weighted(const Place& place, const float* const* corrections, const double* weight,
                                       float* out) const {
  const size_t n = size_t(vertex_count_) * 3;
  const Span& span = spans_[place.span];
  std::fill_n(out, n, 0.f);
  for (int k = 0; k < kInbetweenStencil; ++k) {
    if (weight[k] == 0.0) continue;
    const float c = float(weight[k]);
    const float* d = corrections[k];
    for (size_t j = 0; j < n; ++j) out[j] += c * d[j];
  }
  if (span.motions_end > span.motions_begin) apply_model(span, place.tau, 1.f, out);
}

}  // namespace dcurve
