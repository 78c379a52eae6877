// The Fit predictor over the fast traversal (format_spec/residual.md section 10.7): the
// least-squares affine function of position through up to 16 earlier vertices, with weights
// from one shape. A low-rank basis vector is a smooth field over the mean shape, which Fit
// predicts far better than a parallelogram; its weights are computed once per payload, from
// the chunk's first pseudo-frame (the mean), so a decoder pays for them once at open.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/fast_traversal.h"
#include "codec/common/low_rank.h"
#include "codec/common/predictors.h"

namespace dcurve {

struct FastFit {
  // Position i's set: refs[offsets[i] .. offsets[i+1]), positions of the fast traversal
  // before i (so a frame's corrections are read in traversal order), with weights in the
  // same order (the first of each set is 0: its value is the origin of the others').
  std::vector<uint32_t> offsets, refs;
  std::vector<int32_t> weights;
  size_t bytes() const { return (offsets.capacity() + refs.capacity() + weights.capacity()) * 4; }
};

// The Fit sets of t's positions over the edges of `faces` (V = t.order.size() vertices),
// weighted by the shape `geometry` (V * 3 grid values by vertex id).
FastFit fast_fit(const std::vector<uint32_t>& faces, const FastTraversal& t, const int32_t* geometry);

// What Fit predicts for position i's three axes (p[0..2]) from the corrections e
// (position-major, 3 per position) of the positions before it: 0 for an empty set, else
// e(u_0) plus the weighted differences to it. The encoder's form (residuals, snapping); the
// decoder computes the same sums for all of a basis's vectors at once
// (codec/decompress/fast_fit_decoder.cpp). Basis values (|e| <= 2^24) and |w| <= 2^20 keep
// the sums within 2^50.
inline void fast_fit_position(const FastFit& fit, size_t i, const int64_t* e, int64_t* p) {
  const uint32_t begin = fit.offsets[i], end = fit.offsets[i + 1];
  if (begin == end) {
    p[0] = p[1] = p[2] = 0;
    return;
  }
  const int64_t* e0 = e + size_t(fit.refs[begin]) * 3;
  int64_t s0 = 0, s1 = 0, s2 = 0;
  for (uint32_t k = begin + 1; k < end; ++k) {
    const int64_t w = fit.weights[k];
    const int64_t* x = e + size_t(fit.refs[k]) * 3;
    s0 += w * (x[0] - e0[0]);
    s1 += w * (x[1] - e0[1]);
    s2 += w * (x[2] - e0[2]);
  }
  p[0] = e0[0] + round_shift(s0, 16);  // / kFitUnit, rounded half up
  p[1] = e0[1] + round_shift(s1, 16);
  p[2] = e0[2] + round_shift(s2, 16);
}

}  // namespace dcurve
