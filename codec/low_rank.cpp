#include "codec/low_rank.h"

#include <algorithm>
#include <cstdlib>

#include "codec/int_coder.h"
#include "codec/range_coder.h"

namespace dcurve {
namespace {
// Coefficients follow smooth trajectories: coefficient i (frame-major, K per frame) is
// predicted by linear extrapolation from the same component's two previous frames
// (constant from one, 0 for frame 0), and only the difference is written.
int64_t predicted_coeff(const std::vector<int32_t>& c, size_t i, size_t K) {
  if (i >= 2 * K) return 2 * int64_t(c[i - K]) - int64_t(c[i - 2 * K]);
  return i >= K ? int64_t(c[i - K]) : 0;
}

// Bit 7 of the component byte: the differences are range-coded (format 2.1), not svarints.
constexpr uint8_t kRangeCoded = 0x80;
// Bit 7 of the mean-shift byte: K per-component coefficient shifts follow (format 2.3).
constexpr uint8_t kCoeffShifts = 0x80;
// Bit 6 of the mean-shift byte: frame poses follow the basis payload (format 2.5). The mean
// shift itself needs bits 0-4 (at most 30); bit 5 is reserved and must be 0.
constexpr uint8_t kPosed = 0x40;
constexpr uint8_t kMeanShiftMask = 0x1f;

// A range-coded stream may hold many values per byte; a decoder allocates F * K values only
// when F * K <= 4096 + 64 * stream bytes (the writer keeps svarints beyond that).
bool range_count_plausible(uint64_t count, uint64_t stream_bytes) { return count <= 4096 + 64 * stream_bytes; }

int64_t difference(const std::vector<int32_t>& c, size_t i, size_t K) {
  return int64_t(c[i]) - predicted_coeff(c, i, K);
}

// Magnitude context of stored coefficient i with per-component shifts (2.3): the class of the
// same component's difference one frame earlier (6 for frame 0). Shifted components differ in
// magnitude by orders, which one shared context averages away.
constexpr int kCoeffContexts = 7;
int coeff_context(const std::vector<int32_t>& c, size_t i, size_t K) {
  if (i < K) return 6;
  const uint64_t m = uint64_t(std::abs(difference(c, i - K, K)));
  return m == 0 ? 0 : m == 1 ? 1 : m < 4 ? 2 : m < 16 ? 3 : m < 256 ? 4 : 5;
}

std::vector<uint8_t> range_coded_differences(const std::vector<int32_t>& stored, size_t K, bool contexts) {
  RangeEncoder enc;
  AdaptiveIntCoder coder(contexts ? kCoeffContexts : 1, 1);
  for (size_t i = 0; i < stored.size(); ++i)
    coder.encode(enc, contexts ? coeff_context(stored, i, K) : 0, 0, difference(stored, i, K));
  return enc.finish();
}

// Reads a range-coded stream of `count` values (stream_size varint, then the stream) into
// *out through store(i, value), which checks each value's range: the inverse of
// range_coded_differences. False on a size the remaining bytes or the count cannot match, a
// rejected value, or a stream that does not end exactly.
template <class Store>
bool decode_differences(ByteReader& r, uint64_t count, size_t K, bool contexts, std::vector<int32_t>* out,
                        const Store& store) {
  const uint64_t stream_size = r.varint();
  if (!r.ok || stream_size > r.remaining() || !range_count_plausible(count, stream_size)) return false;
  RangeDecoder dec(r.take(size_t(stream_size)), size_t(stream_size));
  AdaptiveIntCoder coder(contexts ? kCoeffContexts : 1, 1);
  out->assign(size_t(count), 0);
  for (size_t i = 0; i < out->size(); ++i) {
    const int ctx = contexts ? coeff_context(*out, i, K) : 0;
    if (!store(i, predicted_coeff(*out, i, K) + coder.decode(dec, ctx, 0))) return false;
  }
  return dec.at_clean_end();
}

bool has_coeff_shifts(const LowRankModel& lr) {
  return std::any_of(lr.coeff_shifts.begin(), lr.coeff_shifts.end(), [](uint8_t s) { return s > 0; });
}
}  // namespace

std::vector<uint8_t> low_rank_bytes(const Model& m) {
  const LowRankModel& lr = m.low_rank;
  const size_t K = lr.components;
  const bool shifted = has_coeff_shifts(lr);
  // The coefficients as stored: divided by their component's 2^shift (exact by contract).
  std::vector<int32_t> stored = lr.coeffs;
  if (shifted)
    for (size_t i = 0; i < stored.size(); ++i)
      stored[i] = int32_t(int64_t(stored[i]) / (int64_t(1) << lr.coeff_shifts[i % K]));
  // Svarints, or the adaptive range coder when that is smaller: the differences of one
  // file have similar magnitudes, which a varint's fixed 7-bit groups do not exploit.
  ByteWriter varints;
  for (size_t i = 0; i < stored.size(); ++i) varints.varint(zigzag_encode(difference(stored, i, K)));
  const std::vector<uint8_t> stream = range_coded_differences(stored, K, shifted);
  ByteWriter sized;
  sized.varint(stream.size());
  const bool ranged = range_count_plausible(stored.size(), stream.size()) &&
                      sized.size() + stream.size() < varints.size();
  ByteWriter w;
  w.u8(uint8_t(lr.components | (ranged ? kRangeCoded : 0)));
  w.u8(uint8_t(lr.shift));
  const bool posed = !lr.poses.empty();
  w.u8(uint8_t(lr.mean_shift | (shifted ? kCoeffShifts : 0) | (posed ? kPosed : 0)));
  if (shifted)
    for (uint8_t s : lr.coeff_shifts) w.u8(s);
  if (ranged) {
    w.varint(stream.size());
    w.bytes(stream.data(), stream.size());
  } else {
    w.bytes(varints.data().data(), varints.size());
  }
  w.varint(lr.basis_payload.size());
  w.bytes(lr.basis_payload.data(), lr.basis_payload.size());
  if (posed) {
    // Poses move smoothly from frame to frame, as coefficients do: the same extrapolation
    // and the same range coder, one "component" per pose value.
    for (int32_t c : lr.pose_centre) w.varint(zigzag_encode(c));
    const std::vector<uint8_t> poses = range_coded_differences(lr.poses, kLowRankPoseValues, true);
    w.varint(poses.size());
    w.bytes(poses.data(), poses.size());
  }
  return std::move(w.data());
}

bool parse_low_rank(ByteReader& r, Model* m) {
  LowRankModel& lr = m->low_rank;
  const uint8_t first = r.u8();
  const bool ranged = first & kRangeCoded;
  lr.components = first & ~kRangeCoded;
  lr.shift = r.u8();
  const uint8_t third = r.u8();
  lr.mean_shift = third & kMeanShiftMask;
  if (!r.ok || lr.components == 0 || lr.components > kMaxLowRankComponents || lr.shift > kMaxLowRankShift ||
      lr.mean_shift > lr.shift || (third & ~(kMeanShiftMask | kCoeffShifts | kPosed)) != 0)
    return false;
  const size_t K = lr.components;
  lr.coeff_shifts.clear();
  if (third & kCoeffShifts) {
    for (size_t k = 0; k < K; ++k) lr.coeff_shifts.push_back(r.u8());
    if (!r.ok) return false;
    for (uint8_t s : lr.coeff_shifts)
      if (s > lr.shift) return false;
  }
  const uint64_t count = uint64_t(m->meta.frame_count) * K;
  // Stored values first (the extrapolation runs on them), scaled once all are read.
  auto store = [&](size_t i, int64_t c) {
    if (c < -kMaxLowRankCoeff || c > kMaxLowRankCoeff) return false;
    lr.coeffs[i] = int32_t(c);
    return true;
  };
  if (ranged) {
    if (!decode_differences(r, count, K, !lr.coeff_shifts.empty(), &lr.coeffs, store)) return false;
  } else {
    if (count > r.remaining()) return false;  // >= 1 byte per coefficient
    lr.coeffs.resize(size_t(count));
    for (size_t i = 0; i < lr.coeffs.size(); ++i) {
      int64_t c = 0;
      if (!add_zigzag_delta(predicted_coeff(lr.coeffs, i, K), r.varint(), &c) || !store(i, c)) return false;
    }
  }
  if (!lr.coeff_shifts.empty())
    for (size_t i = 0; i < lr.coeffs.size(); ++i) {
      const int64_t c = int64_t(lr.coeffs[i]) * (int64_t(1) << lr.coeff_shifts[i % K]);
      if (c < -kMaxLowRankCoeff || c > kMaxLowRankCoeff) return false;
      lr.coeffs[i] = int32_t(c);
    }
  const uint64_t n = r.varint();
  const uint8_t* p = r.ok && n <= r.remaining() ? r.take(size_t(n)) : nullptr;
  if (!p) return false;
  lr.basis_payload.assign(p, p + n);
  lr.poses.clear();
  if (third & kPosed) {
    for (int32_t& c : lr.pose_centre) {
      const int64_t v = zigzag_decode(r.varint());
      if (!r.ok || !low_rank_pose_centre_ok(v)) return false;
      c = int32_t(v);
    }
    auto store_pose = [&](size_t i, int64_t v) {
      if (!low_rank_pose_value_ok(i, v)) return false;
      lr.poses[i] = int32_t(v);
      return true;
    };
    const uint64_t values = uint64_t(m->meta.frame_count) * kLowRankPoseValues;
    if (!decode_differences(r, values, kLowRankPoseValues, true, &lr.poses, store_pose)) return false;
  }
  return r.ok;
}

namespace {
// acc[i] += c * b[i]: the low-rank prediction's inner loop, most of a low-rank file's decode.
// Built twice on x86-64 (AVX2 and baseline), picked at load time: AVX2 does four of the
// widening 32 x 32 -> 64-bit products at once. Integer arithmetic, so both give the same sums.
#if defined(__x86_64__) && defined(__GNUC__) && defined(__linux__)
#define DCURVE_MULTIVERSION __attribute__((target_clones("avx2", "default")))
#else
#define DCURVE_MULTIVERSION
#endif
template <class Basis>
DCURVE_MULTIVERSION void multiply_add(int64_t* acc, int32_t c, const Basis* b, size_t n) {
  for (size_t i = 0; i < n; ++i) acc[i] += int64_t(c) * int64_t(int32_t(b[i]));
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
