#include "codec/common/low_rank.h"

#include <algorithm>

namespace dcurve {
namespace {
// Values per tile: a tile's sums (4 KB) stay in L1 while all K basis vectors are added, where
// a whole frame's sums would pass through memory once per component.
constexpr size_t kTile = 512;
constexpr int64_t kFrameLimit = int64_t(1) << 30;  // as the PDE model's grid prediction

// out[i] for one tile of `count` values at `begin`: mean * 2^(shift - mean_shift) plus the
// frame's coefficients c times the basis, rounded by 2^shift and clamped. |mean| * 2^30 <
// 2^61 and 64 products of at most 2^48: |sum| < 2^61 + 2^54.
// Inlined into each build of frame_values below, so each is compiled for its instruction set.
#if defined(__GNUC__)
#define DCURVE_INLINE inline __attribute__((always_inline))
#else
#define DCURVE_INLINE inline
#endif
template <class Basis>
DCURVE_INLINE void tile_values(const LowRankModel& lr, const int32_t* c, const int32_t* mean, const Basis* basis,
                               size_t n, size_t begin, size_t count, int32_t* out) {
  int64_t acc[kTile];
  const int64_t up = int64_t(1) << (lr.shift - lr.mean_shift);
  for (size_t i = 0; i < count; ++i) acc[i] = int64_t(mean[begin + i]) * up;
  for (uint32_t k = 0; k < lr.components; ++k) {
    if (c[k] == 0) continue;
    const int64_t ck = c[k];
    const Basis* b = basis + size_t(k) * n + begin;
    for (size_t i = 0; i < count; ++i) acc[i] += ck * int64_t(b[i]);
  }
  // round_shift(acc, shift) as a shift of a non-negative value, so it vectorizes: |acc| <
  // 2^61 + 2^54 (above), so acc + half + 2^62 lies in [0, 2^63), and 2^62 is a multiple of
  // 2^shift (shift <= 30).
  const uint32_t s = lr.shift;
  const int64_t bias = int64_t(1) << 62, half = s ? int64_t(1) << (s - 1) : 0;
  for (size_t i = 0; i < count; ++i) {
    const int64_t rounded = ((acc[i] + half + bias) >> s) - (bias >> s);
    out[begin + i] = int32_t(std::clamp(rounded, -kFrameLimit, kFrameLimit));
  }
}

// The frame's sums tile by tile: most of a low-rank file's decode. Built twice on x86-64
// (AVX2 and baseline), picked at load time: AVX2 does four of the widening 32 x 32 -> 64-bit
// products at once. Integer arithmetic, so both give the same values. GCC only, not under
// the sanitizers (whose runtimes and load-time resolvers do not mix).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && \
    !defined(__SANITIZE_ADDRESS__)
#define DCURVE_MULTIVERSION __attribute__((target_clones("avx2", "default")))
#else
#define DCURVE_MULTIVERSION
#endif
// Two plain functions, not a template: clang accepts target_clones on functions only.
DCURVE_MULTIVERSION void frame_values(const LowRankModel& lr, const int32_t* c, const int32_t* mean,
                                      const int16_t* basis, size_t n, int32_t* out) {
  for (size_t begin = 0; begin < n; begin += kTile) tile_values(lr, c, mean, basis, n, begin, std::min(kTile, n - begin), out);
}
DCURVE_MULTIVERSION void frame_values(const LowRankModel& lr, const int32_t* c, const int32_t* mean,
                                      const int32_t* basis, size_t n, int32_t* out) {
  for (size_t begin = 0; begin < n; begin += kTile) tile_values(lr, c, mean, basis, n, begin, std::min(kTile, n - begin), out);
}

// Format 2.5: each vertex's three values mapped by frame f's pose.
void apply_pose(const LowRankModel& lr, uint32_t f, size_t n, int32_t* out) {
  const int32_t* pose = lr.poses.data() + size_t(f) * kLowRankPoseValues;
  for (size_t v = 0; v + 2 < n; v += 3) {
    int64_t d[3];
    for (int b = 0; b < 3; ++b)
      d[b] = std::clamp(int64_t(out[v + size_t(b)]) - lr.pose_centre[b], -kMaxLowRankPoseReach, kMaxLowRankPoseReach);
    for (int a = 0; a < 3; ++a) {
      const int64_t turned = int64_t(pose[3 * a]) * d[0] + int64_t(pose[3 * a + 1]) * d[1] + int64_t(pose[3 * a + 2]) * d[2];
      const int64_t x = int64_t(lr.pose_centre[a]) + pose[9 + a] + round_shift(turned, kLowRankPoseShift);
      out[v + size_t(a)] = int32_t(std::clamp(x, -kFrameLimit, kFrameLimit));
    }
  }
}

template <class Basis>
void frame_from(const LowRankModel& lr, uint32_t f, const int32_t* mean, const Basis* basis, size_t n, int32_t* out) {
  frame_values(lr, lr.coeffs.data() + size_t(f) * lr.components, mean, basis, n, out);
  if (!lr.poses.empty()) apply_pose(lr, f, n, out);
}
}  // namespace

void LowRankTables::assign(const std::vector<int32_t>& mean_and_basis, size_t n) {
  mean.assign(mean_and_basis.begin(), mean_and_basis.begin() + std::ptrdiff_t(n));
  const auto first = mean_and_basis.begin() + std::ptrdiff_t(n);
  const bool narrow = std::all_of(first, mean_and_basis.end(), [](int32_t v) { return v >= INT16_MIN && v <= INT16_MAX; });
  basis16.clear();
  basis32.clear();
  if (narrow) basis16.assign(first, mean_and_basis.end());
  else basis32.assign(first, mean_and_basis.end());
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const int32_t* mean_and_basis, size_t n, int32_t* out) {
  frame_from(lr, f, mean_and_basis, mean_and_basis + n, n, out);
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const LowRankTables& t, size_t n, int32_t* out) {
  if (t.basis32.empty()) frame_from(lr, f, t.mean.data(), t.basis16.data(), n, out);
  else frame_from(lr, f, t.mean.data(), t.basis32.data(), n, out);
}

}  // namespace dcurve
