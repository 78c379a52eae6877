#include "codec/common/low_rank.h"

#include <algorithm>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#elif defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

namespace dcurve {
namespace {
// Values per tile: a tile's sums (4 KB) stay in L1 while all K basis vectors are added, where
// a whole frame's sums would pass through memory once per component.
constexpr size_t kTile = 512;
constexpr int64_t kFrameLimit = int64_t(1) << 30;  // as the PDE model's grid prediction

// The tiles' steps are inlined into each build of frame_values below, so each is compiled for
// its instruction set.
#if defined(__GNUC__)
#define DCURVE_INLINE inline __attribute__((always_inline))
#else
#define DCURVE_INLINE inline
#endif

// round_shift(acc, s) clamped, as a shift of a non-negative value, so it vectorizes: |acc| <
// 2^61 + 2^54 (tile_values), so acc + half + 2^62 lies in [0, 2^63), and 2^62 is a multiple of
// 2^s (s <= 30).
DCURVE_INLINE void round_tile(const int64_t* acc, size_t count, uint32_t s, int32_t* out) {
  const int64_t bias = int64_t(1) << 62, half = s ? int64_t(1) << (s - 1) : 0;
  for (size_t i = 0; i < count; ++i) {
    const int64_t rounded = ((acc[i] + half + bias) >> s) - (bias >> s);
    out[i] = int32_t(std::clamp(rounded, -kFrameLimit, kFrameLimit));
  }
}

// out[i] for one tile of `count` values at `begin`: mean * 2^(shift - mean_shift) plus the
// frame's coefficients c times the basis, rounded by 2^shift and clamped. |mean| * 2^30 <
// 2^61 and 64 products of at most 2^48: |sum| < 2^61 + 2^54.
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
  round_tile(acc, count, lr.shift, out + begin);
}

// tile_values for the component pairs of LowRankTables::pairs16, in int64.
DCURVE_INLINE void tile_values_paired(const LowRankModel& lr, const int32_t* c, const int32_t* mean,
                                      const int16_t* pairs, size_t n, size_t begin, size_t count, int32_t* out) {
  int64_t acc[kTile];
  const int64_t up = int64_t(1) << (lr.shift - lr.mean_shift);
  for (size_t i = 0; i < count; ++i) acc[i] = int64_t(mean[begin + i]) * up;
  for (uint32_t k = 0; k < lr.components; k += 2) {
    const int64_t c0 = c[k], c1 = k + 1 < lr.components ? c[k + 1] : 0;
    if (c0 == 0 && c1 == 0) continue;
    const int16_t* b = pairs + (size_t(k / 2) * n + begin) * 2;
    for (size_t i = 0; i < count; ++i) acc[i] += c0 * int64_t(b[2 * i]) + c1 * int64_t(b[2 * i + 1]);
  }
  round_tile(acc, count, lr.shift, out + begin);
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
                                      const int32_t* basis, size_t n, int32_t* out) {
  for (size_t begin = 0; begin < n; begin += kTile) tile_values(lr, c, mean, basis, n, begin, std::min(kTile, n - begin), out);
}
DCURVE_MULTIVERSION void frame_values_paired(const LowRankModel& lr, const int32_t* c, const int32_t* mean,
                                             const int16_t* pairs, size_t n, int32_t* out) {
  for (size_t begin = 0; begin < n; begin += kTile)
    tile_values_paired(lr, c, mean, pairs, n, begin, std::min(kTile, n - begin), out);
}
// The int32 form of a frame's sums, for a frame whose every partial sum provably stays below
// 2^30 with the rounding's half (narrow_coefficients): its component pairs with a non-zero
// coefficient, the two 16-bit coefficients as one 32-bit word (low half first, as the
// multiply-adds pmaddwd and i32x4.dot_i16x8 take them) beside the pair's values, and the
// rounding of tile_values with a bias of 2^30, so acc + add lies in [0, 2^31).
struct NarrowPairs {
  int32_t words[kMaxLowRankComponents / 2 + 1];
  const int16_t* rows[kMaxLowRankComponents / 2 + 1];
  uint32_t count = 0;
  int up_shift = 0, shift = 0;
  int32_t add = 0, sub = 0;  // acc -> ((acc + add) >> shift) - sub
};
NarrowPairs narrow_pairs(const LowRankModel& lr, const int16_t* c, uint32_t pair_count, const int16_t* pairs,
                         size_t n) {
  NarrowPairs p;
  for (uint32_t j = 0; j < pair_count; ++j) {
    const int32_t word = int32_t(uint32_t(uint16_t(c[2 * j])) | uint32_t(uint16_t(c[2 * j + 1])) << 16);
    if (word == 0) continue;
    p.words[p.count] = word;
    p.rows[p.count++] = pairs + size_t(j) * n * 2;
  }
  p.up_shift = int(lr.shift - lr.mean_shift);
  p.shift = int(lr.shift);
  const int32_t bias = int32_t(1) << 30, half = p.shift ? int32_t(1) << (p.shift - 1) : 0;
  p.add = half + bias;
  p.sub = bias >> p.shift;
  return p;
}

// Values [begin, end) of the int32 sums, tile by tile, component pair after pair (a loop a
// vectorizer can take): the vector forms' tail, and the whole frame on CPUs without them; p
// by value, as narrow_values_avx2's.
void narrow_values_plain(const NarrowPairs p, const int32_t* mean, size_t begin, size_t end, int32_t* out) {
  int32_t acc[kTile];
  for (size_t tile = begin; tile < end; tile += kTile) {
    const size_t count = std::min(kTile, end - tile);
    for (size_t i = 0; i < count; ++i) acc[i] = mean[tile + i] * (int32_t(1) << p.up_shift);
    for (uint32_t k = 0; k < p.count; ++k) {
      const int32_t c0 = int16_t(p.words[k]), c1 = int16_t(p.words[k] >> 16);
      const int16_t* b = p.rows[k] + 2 * tile;
      for (size_t i = 0; i < count; ++i) acc[i] += int32_t(b[2 * i]) * c0 + int32_t(b[2 * i + 1]) * c1;
    }
    for (size_t i = 0; i < count; ++i) out[tile + i] = ((acc[i] + p.add) >> p.shift) - p.sub;
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
// The int32 sums with AVX2's 16-bit multiply-add (vpmaddwd: eight values of a component pair
// per instruction), eight values at a time across all pairs in a register. p by value: a copy
// the stores to out cannot alias, so its rows and words stay in registers.
__attribute__((target("avx2"))) void narrow_values_avx2(const NarrowPairs p, const int32_t* mean, size_t n,
                                                        int32_t* out) {
  const __m256i add = _mm256_set1_epi32(p.add), sub = _mm256_set1_epi32(p.sub);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    __m256i acc = _mm256_slli_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(mean + i)), p.up_shift);
    for (uint32_t k = 0; k < p.count; ++k) {
      const __m256i b = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p.rows[k] + 2 * i));
      acc = _mm256_add_epi32(acc, _mm256_madd_epi16(b, _mm256_set1_epi32(p.words[k])));
    }
    acc = _mm256_sub_epi32(_mm256_srai_epi32(_mm256_add_epi32(acc, add), p.shift), sub);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + i), acc);
  }
  // The tail is a call GCC turns into a jump without clearing the upper halves, which left
  // every later SSE instruction of the frame paying for the transition (measured: 1.2x).
  _mm256_zeroupper();
  narrow_values_plain(p, mean, i, n, out);
}
bool has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

#if defined(__wasm_simd128__)
// The int32 sums with WebAssembly's i32x4.dot_i16x8_s, the same multiply-add as vpmaddwd on
// four values at a time; p by value, as narrow_values_avx2's.
void narrow_values_wasm(const NarrowPairs p, const int32_t* mean, size_t n, int32_t* out) {
  const v128_t add = wasm_i32x4_splat(p.add), sub = wasm_i32x4_splat(p.sub);
  v128_t coeffs[kMaxLowRankComponents / 2 + 1];
  for (uint32_t k = 0; k < p.count; ++k) coeffs[k] = wasm_i32x4_splat(p.words[k]);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {  // two independent sums: the adds of one do not wait on the other
    v128_t lo = wasm_i32x4_shl(wasm_v128_load(mean + i), p.up_shift);
    v128_t hi = wasm_i32x4_shl(wasm_v128_load(mean + i + 4), p.up_shift);
    for (uint32_t k = 0; k < p.count; ++k) {
      lo = wasm_i32x4_add(lo, wasm_i32x4_dot_i16x8(wasm_v128_load(p.rows[k] + 2 * i), coeffs[k]));
      hi = wasm_i32x4_add(hi, wasm_i32x4_dot_i16x8(wasm_v128_load(p.rows[k] + 2 * i + 8), coeffs[k]));
    }
    wasm_v128_store(out + i, wasm_i32x4_sub(wasm_i32x4_shr(wasm_i32x4_add(lo, add), p.shift), sub));
    wasm_v128_store(out + i + 4, wasm_i32x4_sub(wasm_i32x4_shr(wasm_i32x4_add(hi, add), p.shift), sub));
  }
  narrow_values_plain(p, mean, i, n, out);
}
#endif

void frame_values_narrow(const LowRankModel& lr, const int16_t* c, uint32_t pair_count, const int32_t* mean,
                         const int16_t* pairs, size_t n, int32_t* out) {
  const NarrowPairs p = narrow_pairs(lr, c, pair_count, pairs, n);
#if defined(__x86_64__) && defined(__GNUC__)
  if (has_avx2()) return narrow_values_avx2(p, mean, n, out);
#elif defined(__wasm_simd128__)
  return narrow_values_wasm(p, mean, n, out);
#endif
  narrow_values_plain(p, mean, 0, n, out);
}

// Frame f's coefficients in 16 bits, padded to whole pairs, when every partial sum of its
// values (mean term, products, rounding half) provably stays below 2^30; else false.
bool narrow_coefficients(const LowRankModel& lr, const LowRankTables& t, uint32_t f, int16_t* c16) {
  const int32_t* c = lr.coeffs.data() + size_t(f) * lr.components;
  const uint32_t s = lr.shift;
  uint64_t bound = (uint64_t(t.mean_max) << (s - lr.mean_shift)) + (s ? uint64_t(1) << (s - 1) : 0);
  for (uint32_t k = 0; k < lr.components; ++k) {
    if (c[k] < INT16_MIN || c[k] > INT16_MAX) return false;
    c16[k] = int16_t(c[k]);
    bound += uint64_t(c[k] < 0 ? -int64_t(c[k]) : c[k]) * t.basis_max[k];
    if (bound >= uint64_t(1) << 30) return false;
  }
  if (lr.components % 2) c16[lr.components] = 0;
  return true;
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
uint32_t magnitude(int64_t v) { return uint32_t(v < 0 ? -v : v); }
}  // namespace

void LowRankTables::assign(const std::vector<int32_t>& mean_and_basis, size_t n) {
  mean.assign(mean_and_basis.begin(), mean_and_basis.begin() + std::ptrdiff_t(n));
  const int32_t* basis = mean_and_basis.data() + n;
  const size_t K = n ? (mean_and_basis.size() - n) / n : 0;
  int32_t lo = 0, hi = 0;
  for (int32_t v : mean) lo = std::min(lo, v), hi = std::max(hi, v);
  mean_max = std::max(magnitude(lo), magnitude(hi));
  // One pass per component for its range: both the 16-bit test and the maxima of the bound.
  basis_max.assign(K, 0);
  bool narrow = true;
  for (size_t k = 0; k < K; ++k) {
    lo = hi = 0;
    for (size_t i = 0; i < n; ++i) lo = std::min(lo, basis[k * n + i]), hi = std::max(hi, basis[k * n + i]);
    basis_max[k] = std::max(magnitude(lo), magnitude(hi));
    narrow = narrow && lo >= INT16_MIN && hi <= INT16_MAX;
  }
  pairs16.clear();
  basis32.clear();
  if (!narrow) {
    basis32.assign(basis, basis + K * n);
    return;
  }
  pairs16.resize((K + 1) / 2 * n * 2);
  for (size_t k = 0; k < K; k += 2) {
    const int32_t* a = basis + k * n;
    const int32_t* b = k + 1 < K ? a + n : nullptr;  // an odd K's last pair is padded with zeros
    int16_t* out = pairs16.data() + k * n;
    for (size_t i = 0; i < n; ++i) {
      out[2 * i] = int16_t(a[i]);
      out[2 * i + 1] = b ? int16_t(b[i]) : int16_t(0);
    }
  }
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const int32_t* mean_and_basis, size_t n, int32_t* out) {
  frame_from(lr, f, mean_and_basis, mean_and_basis + n, n, out);
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const LowRankTables& t, size_t n, int32_t* out) {
  int16_t c16[kMaxLowRankComponents + 1];
  if (!t.basis32.empty() || lr.components == 0) {
    frame_from(lr, f, t.mean.data(), t.basis32.data(), n, out);
    return;
  }
  if (narrow_coefficients(lr, t, f, c16))
    frame_values_narrow(lr, c16, (lr.components + 1) / 2, t.mean.data(), t.pairs16.data(), n, out);
  else
    frame_values_paired(lr, lr.coeffs.data() + size_t(f) * lr.components, t.mean.data(), t.pairs16.data(), n, out);
  if (!lr.poses.empty()) apply_pose(lr, f, n, out);
}

}  // namespace dcurve
