#include "codec/common/low_rank.h"

#include <algorithm>

namespace dcurve {
namespace {
// acc[i] += c * b[i]: the low-rank prediction's inner loop, most of a low-rank file's decode.
// Built twice on x86-64 (AVX2 and baseline), picked at load time: AVX2 does four of the
// widening 32 x 32 -> 64-bit products at once. Integer arithmetic, so both give the same sums.
// GCC only, not under the sanitizers (whose runtimes and load-time resolvers do not mix).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && defined(__linux__) && \
    !defined(__SANITIZE_ADDRESS__)
#define DCURVE_MULTIVERSION __attribute__((target_clones("avx2", "default")))
#else
#define DCURVE_MULTIVERSION
#endif
// Two plain functions, not a template: clang accepts target_clones on functions only.
DCURVE_MULTIVERSION void multiply_add(int64_t* acc, int32_t c, const int16_t* b, size_t n) {
  for (size_t i = 0; i < n; ++i) acc[i] += int64_t(c) * int64_t(b[i]);
}
DCURVE_MULTIVERSION void multiply_add(int64_t* acc, int32_t c, const int32_t* b, size_t n) {
  for (size_t i = 0; i < n; ++i) acc[i] += int64_t(c) * int64_t(b[i]);
}

template <class Basis>
void low_rank_sums(const LowRankModel& lr, uint32_t f, const int32_t* mean, const Basis* basis, size_t n,
                   int64_t* acc) {
  const uint32_t K = lr.components;
  const int32_t* c = lr.coeffs.data() + size_t(f) * K;
  const uint32_t up = lr.shift - lr.mean_shift;
  // |mean| * 2^30 < 2^61 and 64 products of at most 2^48: the sum stays below 2^62. One
  // component at a time, so every pass reads one basis vector in order.
  for (size_t i = 0; i < n; ++i) acc[i] = int64_t(mean[i]) * (int64_t(1) << up);
  for (uint32_t k = 0; k < K; ++k)
    if (c[k] != 0) multiply_add(acc, c[k], basis + size_t(k) * n, n);
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

namespace {
// The rounded, clamped sums, then (format 2.5) each vertex mapped by frame f's pose.
void finish_frame(const LowRankModel& lr, uint32_t f, const int64_t* acc, size_t n, int32_t* out) {
  constexpr int64_t kLimit = int64_t(1) << 30;  // as the PDE model's grid prediction
  for (size_t i = 0; i < n; ++i) out[i] = int32_t(std::clamp(round_shift(acc[i], lr.shift), -kLimit, kLimit));
  if (lr.poses.empty()) return;
  const int32_t* pose = lr.poses.data() + size_t(f) * kLowRankPoseValues;
  for (size_t v = 0; v + 2 < n; v += 3) {
    int64_t d[3];
    for (int b = 0; b < 3; ++b)
      d[b] = std::clamp(int64_t(out[v + size_t(b)]) - lr.pose_centre[b], -kMaxLowRankPoseReach, kMaxLowRankPoseReach);
    for (int a = 0; a < 3; ++a) {
      const int64_t turned = int64_t(pose[3 * a]) * d[0] + int64_t(pose[3 * a + 1]) * d[1] + int64_t(pose[3 * a + 2]) * d[2];
      const int64_t x = int64_t(lr.pose_centre[a]) + pose[9 + a] + round_shift(turned, kLowRankPoseShift);
      out[v + size_t(a)] = int32_t(std::clamp(x, -kLimit, kLimit));
    }
  }
}
}  // namespace

void low_rank_frame(const LowRankModel& lr, uint32_t f, const int32_t* mean_and_basis, size_t n, int32_t* out,
                    int64_t* scratch) {
  low_rank_sums(lr, f, mean_and_basis, mean_and_basis + n, n, scratch);
  finish_frame(lr, f, scratch, n, out);
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const LowRankTables& t, size_t n, int32_t* out,
                    int64_t* scratch) {
  if (t.basis32.empty()) low_rank_sums(lr, f, t.mean.data(), t.basis16.data(), n, scratch);
  else low_rank_sums(lr, f, t.mean.data(), t.basis32.data(), n, scratch);
  finish_frame(lr, f, scratch, n, out);
}

}  // namespace dcurve
