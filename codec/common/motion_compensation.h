// Motion-compensated prediction: the base prediction of a cluster of vertices is an affine
// map of a reference frame's decoded grid values. The map is stored in fixed point and
// applied in int64 arithmetic, so encoder and decoder compute identical integers on every
// platform (no floating point, so no FMA contraction or compiler differences).
// format_spec/residual.md, "Motion compensation", is the normative description.
#pragma once
#include <cstdint>

#include "codec/common/predictors.h"

namespace dcurve {

// Matrix entries are stored as deviations from the identity in units of 2^-14.
constexpr int kMotionFractionBits = 14;
constexpr int64_t kMotionOne = int64_t(1) << kMotionFractionBits;
// Stored ranges (a decoder rejects anything outside): matrix deviation |m| <= 2^16 (matrix
// entries within [-3, 5]), translation |t| <= 2^24 grid steps. They keep every
// intermediate of the prediction and of the spatial corrections far inside int64.
constexpr int32_t kMaxMotionMatrix = int32_t(1) << 16;
constexpr int32_t kMaxMotionShift = int32_t(1) << 24;

// One output axis of the map: y_a = c_a + t + round(sum_b (delta_ab * 2^14 + m[b]) * (x_b - c_b) / 2^14),
// with c the cluster's centre in the reference frame (cluster_centre).
struct MotionRow {
  int32_t m[3] = {0, 0, 0};
  int32_t t = 0;
  bool operator==(const MotionRow& o) const { return m[0] == o.m[0] && m[1] == o.m[1] && m[2] == o.m[2] && t == o.t; }
};

struct MotionTransform {
  MotionRow row[3];
};

inline bool motion_row_valid(const MotionRow& r) {
  for (int32_t m : r.m)
    if (m < -kMaxMotionMatrix || m > kMaxMotionMatrix) return false;
  return r.t >= -kMaxMotionShift && r.t <= kMaxMotionShift;
}

// Floor of the mean of the reference values of the vertices at traversal positions
// [begin, end) (end > begin), per axis: a centre both sides compute exactly.
// ref: the reference frame's values, (v * 3 + axis), grid units.
void cluster_centre(const int32_t* ref, const Traversal& t, uint32_t begin, uint32_t end, int64_t centre[3]);

// The motion-compensated base prediction of `axis` for a vertex whose reference values are
// x[0..2] (grid units): row applied around `centre`. Exact integer arithmetic.
inline int64_t motion_prediction(const MotionRow& row, int axis, const int64_t centre[3], const int32_t* x) {
  int64_t sum = 0;
  for (int b = 0; b < 3; ++b) sum += (int64_t(row.m[b]) + (b == axis ? kMotionOne : 0)) * (int64_t(x[b]) - centre[b]);
  return centre[axis] + row.t + detail::rounded_mean(sum, kMotionOne);
}

}  // namespace dcurve
