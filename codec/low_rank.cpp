#include "codec/low_rank.h"

#include <algorithm>

namespace dcurve {
namespace {
// Coefficients follow smooth trajectories: coefficient i (frame-major, K per frame) is
// predicted by linear extrapolation from the same component's two previous frames
// (constant from one, 0 for frame 0), and only the difference is written.
int64_t predicted_coeff(const std::vector<int32_t>& c, size_t i, size_t K) {
  if (i >= 2 * K) return 2 * int64_t(c[i - K]) - int64_t(c[i - 2 * K]);
  return i >= K ? int64_t(c[i - K]) : 0;
}
}  // namespace

std::vector<uint8_t> low_rank_bytes(const Model& m) {
  const LowRankModel& lr = m.low_rank;
  ByteWriter w;
  w.u8(uint8_t(lr.components));
  w.u8(uint8_t(lr.shift));
  w.u8(uint8_t(lr.mean_shift));
  for (size_t i = 0; i < lr.coeffs.size(); ++i)
    w.varint(zigzag_encode(int64_t(lr.coeffs[i]) - predicted_coeff(lr.coeffs, i, lr.components)));
  w.varint(lr.basis_payload.size());
  w.bytes(lr.basis_payload.data(), lr.basis_payload.size());
  return std::move(w.data());
}

bool parse_low_rank(ByteReader& r, Model* m) {
  LowRankModel& lr = m->low_rank;
  lr.components = r.u8();
  lr.shift = r.u8();
  lr.mean_shift = r.u8();
  if (!r.ok || lr.components == 0 || lr.components > kMaxLowRankComponents || lr.shift > kMaxLowRankShift ||
      lr.mean_shift > lr.shift)
    return false;
  const uint64_t count = uint64_t(m->meta.frame_count) * lr.components;
  if (count > r.remaining()) return false;  // >= 1 byte per coefficient
  lr.coeffs.resize(size_t(count));
  const size_t K = lr.components;
  for (size_t i = 0; i < lr.coeffs.size(); ++i) {
    int64_t c = 0;
    if (!add_zigzag_delta(predicted_coeff(lr.coeffs, i, K), r.varint(), &c) || c < -kMaxLowRankCoeff ||
        c > kMaxLowRankCoeff)
      return false;
    lr.coeffs[i] = int32_t(c);
  }
  const uint64_t n = r.varint();
  const uint8_t* p = r.ok && n <= r.remaining() ? r.take(size_t(n)) : nullptr;
  if (!p) return false;
  lr.basis_payload.assign(p, p + n);
  return r.ok;
}

void low_rank_frame(const LowRankModel& lr, uint32_t f, const int32_t* mean_and_basis, size_t n, int32_t* out) {
  constexpr int64_t kLimit = int64_t(1) << 30;  // as the PDE model's grid prediction
  const uint32_t K = lr.components;
  const int32_t* c = lr.coeffs.data() + size_t(f) * K;
  const uint32_t up = lr.shift - lr.mean_shift;
  for (size_t i = 0; i < n; ++i) {
    // |mean| * 2^30 < 2^61 and 64 products of at most 2^48: the sum stays below 2^62.
    int64_t acc = int64_t(mean_and_basis[i]) * (int64_t(1) << up);
    for (uint32_t k = 0; k < K; ++k) acc += int64_t(c[k]) * int64_t(mean_and_basis[(size_t(k) + 1) * n + i]);
    out[i] = int32_t(std::clamp(round_shift(acc, lr.shift), -kLimit, kLimit));
  }
}

}  // namespace dcurve
