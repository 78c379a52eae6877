#include "encoder/rate/motion_model.h"

#include <algorithm>
#include <cmath>

#include "codec/common/basis.h"
#include "codec/common/container_format.h"
#include "codec/compress/quantize.h"
#include "encoder/fit/fit.h"

namespace dcurve {
namespace {

// Rounds the coefficients of `m` as coarsely as `budget` allows: a coefficient error of at
// most 2^(e-1) changes w by at most 2^(e-1) * sum_ij max|T_i| max|U_j| over the segment's
// tau samples and the curve's u values.
void quantize_for_budget(const CurveFrames& samples, double budget, CurveMotion* m) {
  if (m->basis == Basis::Zero) return;
  const int nt = basis_time_count(m->basis), ns = basis_space_count(m->basis);
  double t[4], s[8], max_t[4] = {0, 0, 0, 0}, max_s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  for (double tau : samples.tau) {
    basis_time(m->basis, m->basis_case, m->time_param, tau, t);
    for (int i = 0; i < nt; ++i) max_t[i] = std::max(max_t[i], std::fabs(t[i]));
  }
  for (double u : samples.u) {
    basis_space(m->basis, m->basis_case, m->space_param, u, s);
    for (int j = 0; j < ns; ++j) max_s[j] = std::max(max_s[j], std::fabs(s[j]));
  }
  double reach = 0;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < ns; ++j) reach += max_t[i] * max_s[j];
  const int exponent = reach > 0 && budget > 0 ? int(std::floor(std::log2(2.0 * budget / reach))) : kCoeffExponentMax;
  quantize_coefficients(m, exponent);
}

}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> plan_segments(uint32_t frame_count, uint32_t segment_frames) {
  std::vector<std::pair<uint32_t, uint32_t>> out;
  const uint32_t last = frame_count > 0 ? frame_count - 1 : 0;
  const uint32_t step = segment_frames == 0 ? 1 : segment_frames;
  if (last == 0) return {{0, 0}};
  uint32_t first = 0;
  while (first < last) {
    uint32_t end = std::min(last, first + step);
    if (last - end < (step + 1) / 2) end = last;  // no stub segment at the end
    out.emplace_back(first, end);
    first = end;
  }
  return out;
}

bool fit_motion_model(const Animation& anim, const Curves& curves, const std::vector<float>& rest,
                      const MotionModelOptions& options, std::vector<Segment>* segments, std::string* error) {
  const uint32_t C = curves.curve_count();
  segments->clear();
  for (auto [first, last] : plan_segments(uint32_t(anim.frames.size()), options.segment_frames)) {
    std::vector<CurveFrames> samples(C);
    for (uint32_t c = 0; c < C; ++c) {
      CurveFrames& s = samples[c];
      const uint32_t begin = curves.offsets[c], end = curves.offsets[c + 1];
      for (uint32_t i = begin; i < end; ++i) s.u.push_back(quantize_curve_u(curves.u[i]));
      for (uint32_t f = first; f <= last; ++f) {
        s.tau.push_back(last > first ? double(f - first) / double(last - first) : 0.0);
        for (uint32_t i = begin; i < end; ++i)
          for (int a = 0; a < 3; ++a) s.xyz.push_back(anim.frames[f][3 * size_t(curves.vertices[i]) + a]);
      }
      if (options.mode == FitMode::Displacement)
        for (uint32_t i = begin; i < end; ++i)
          for (int a = 0; a < 3; ++a) s.rest.push_back(rest[3 * size_t(curves.vertices[i]) + a]);
    }
    FitOptions fo;
    fo.basis = options.basis;
    fo.mode = options.mode;
    fo.max_time_param = options.max_time_param;
    std::vector<CurveFit> fits;
    if (!fit_curves(samples, fo, options.threads, &fits, error)) return false;
    Segment seg;
    seg.first_frame = first;
    seg.last_frame = last;
    seg.mode = options.mode;
    seg.motion.resize(size_t(C) * 3);
    for (uint32_t c = 0; c < C; ++c)
      for (int a = 0; a < 3; ++a) {
        CurveMotion& m = seg.motion[size_t(c) * 3 + a];
        m = fits[c].axis[a].motion;
        quantize_for_budget(samples[c], options.coefficient_error, &m);
      }
    segments->push_back(std::move(seg));
  }
  return true;
}

}  // namespace dcurve
