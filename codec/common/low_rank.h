// The LRNK section: a low-rank (PCA) model of the residual grid that the residual layer's
// Model predictor uses (format_spec/dcrv.md section 10). Everything a prediction depends on
// is integer, so encoder and decoder compute bit-identical values on every platform. The
// payload is written by codec/compress/low_rank_writer.h and read by
// codec/decompress/low_rank_reader.h.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

constexpr uint32_t kMaxLowRankComponents = 64;
constexpr uint32_t kMaxLowRankShift = 30;
// Bounds that keep mean * 2^shift + sum_k coeff * basis inside int64 (< 2^62) for any
// accepted file: |mean| < 2^31 (int32), |coeff|, |basis| <= 2^24, K <= 64.
constexpr int64_t kMaxLowRankCoeff = int64_t(1) << 24;
constexpr int64_t kMaxLowRankBasis = int64_t(1) << 24;
// Frame poses (format 2.5, LowRankModel::poses): per frame a 3 x 3 matrix in units of
// 2^-kLowRankPoseShift, |entries| <= kMaxLowRankPoseMatrix, then a translation in grid units,
// |t| <= kMaxLowRankPoseOffset; the centre too is within kMaxLowRankPoseOffset. A posed-space
// prediction enters the matrix product as its difference to the centre clamped to
// +-kMaxLowRankPoseReach, so every product stays far inside int64 (3 * 2^20 * 2^26 < 2^48).
constexpr uint32_t kLowRankPoseValues = 12;
constexpr uint32_t kLowRankPoseShift = 16;
constexpr int64_t kMaxLowRankPoseMatrix = int64_t(1) << 20;
constexpr int64_t kMaxLowRankPoseOffset = int64_t(1) << 30;
constexpr int64_t kMaxLowRankPoseReach = int64_t(1) << 26;

// Whether v is a valid pose value at index i of LowRankModel::poses (a matrix entry or a
// translation, by i's place in its frame's kLowRankPoseValues), or of the centre (i unused).
inline bool low_rank_pose_value_ok(size_t i, int64_t v) {
  const int64_t limit = i % kLowRankPoseValues < 9 ? kMaxLowRankPoseMatrix : kMaxLowRankPoseOffset;
  return v >= -limit && v <= limit;
}
inline bool low_rank_pose_centre_ok(int64_t c) { return c >= -kMaxLowRankPoseOffset && c <= kMaxLowRankPoseOffset; }

// floor((x + 2^(s-1)) / 2^s) for s >= 1, x for s = 0: x / 2^s rounded half up, written with
// shifts of non-negative values only so it is the same on every compiler. |x| < 2^62.
inline int64_t round_shift(int64_t x, uint32_t s) {
  if (s == 0) return x;
  const int64_t y = x + (int64_t(1) << (s - 1));
  return y >= 0 ? y >> s : -((-y + (int64_t(1) << s) - 1) >> s);
}

// The Model predictor of frame f (grid units, clamped to +-2^30) for n = V * 3 coordinates:
// mean and basis are the decoded pseudo-frames (mean first, then K basis vectors, n each,
// already checked against kMaxLowRankBasis), out receives n values. With poses, each
// vertex's three posed-space values are mapped by frame f's pose (format_spec/dcrv.md
// section 10).
void low_rank_frame(const LowRankModel& lr, uint32_t f, const int32_t* mean_and_basis, size_t n, int32_t* out);

// The decoded mean and basis as a decoder keeps them: the basis in 16 bits when every value
// fits (half the memory; most files), else in 32. In 16 bits the components go in pairs,
// value by value (component 2j's value i, then 2j + 1's; a zero component pads an odd K), so
// a frame whose sums provably stay within 2^30 (low_rank_frame checks per frame; the
// files measured all do) is summed in int32 two components per multiply-add.
struct LowRankTables {
  std::vector<int32_t> mean;
  std::vector<int16_t> pairs16;  // [K / 2 rounded up][n][2]
  std::vector<int32_t> basis32;  // [K][n]
  uint32_t mean_max = 0;              // max |mean|
  std::vector<uint32_t> basis_max;    // per component, max |value|
  // From the decoded pseudo-frames: the mean, then the K basis vectors, n values each.
  void assign(const std::vector<int32_t>& mean_and_basis, size_t n);
  size_t bytes() const {
    return mean.capacity() * 4 + pairs16.capacity() * 2 + basis32.capacity() * 4 + basis_max.capacity() * 4;
  }
};
// low_rank_frame from the tables.
void low_rank_frame(const LowRankModel& lr, uint32_t f, const LowRankTables& tables, size_t n, int32_t* out);

}  // namespace dcurve
