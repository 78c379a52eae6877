#include "codec/decompress/low_rank_reader.h"

#include "codec/common/int_coder.h"
#include "codec/common/low_rank.h"
#include "codec/common/low_rank_format.h"
#include "codec/decompress/range_decoder.h"
#include "codec/decompress/zstd_frame.h"

namespace dcurve {
namespace {
using low_rank_format::coeff_context;
using low_rank_format::kCoeffContexts;
using low_rank_format::kCoeffShifts;
using low_rank_format::kMaxSvarintBytes;
using low_rank_format::kMeanShiftMask;
using low_rank_format::kPackedDifferences;
using low_rank_format::kPosed;
using low_rank_format::kRangeCoded;
using low_rank_format::predicted_coeff;
using low_rank_format::range_count_plausible;

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

// Reads `count` svarint differences (R = 0) into *out through store.
template <class Store>
bool read_varint_differences(ByteReader& r, uint64_t count, size_t K, std::vector<int32_t>* out, const Store& store) {
  if (count > r.remaining()) return false;  // >= 1 byte per value
  out->assign(size_t(count), 0);
  for (size_t i = 0; i < out->size(); ++i) {
    int64_t c = 0;
    if (!add_zigzag_delta(predicted_coeff(*out, i, K), r.varint(), &c) || !store(i, c)) return false;
  }
  return r.ok;
}

// Reads the packed form (Z = 1): the svarints' size, one zstd frame of exactly that many
// bytes, which hold exactly `count` svarints. Sizes are checked before anything is allocated.
template <class Store>
bool read_packed_differences(ByteReader& r, uint64_t count, size_t K, std::vector<int32_t>* out, const Store& store) {
  const uint64_t raw = r.varint(), stored = r.varint();
  if (!r.ok || stored > r.remaining() || raw < count || raw > count * kMaxSvarintBytes ||
      !zstd_size_plausible(raw, stored))
    return false;
  std::vector<uint8_t> bytes;
  if (!decompress_exactly(r.take(size_t(stored)), size_t(stored), raw, &bytes)) return false;
  ByteReader v(bytes.data(), bytes.size());
  return read_varint_differences(v, count, K, out, store) && v.remaining() == 0;
}
}  // namespace

bool parse_low_rank(ByteReader& r, Model* m, bool fast_format) {
  LowRankModel& lr = m->low_rank;
  const uint8_t first = r.u8();
  const bool ranged = first & kRangeCoded;
  lr.components = first & ~kRangeCoded;
  lr.shift = r.u8();
  const uint8_t third = r.u8();
  lr.mean_shift = third & kMeanShiftMask;
  const bool packed = third & kPackedDifferences;
  if (!r.ok || lr.components == 0 || lr.components > kMaxLowRankComponents || lr.shift > kMaxLowRankShift ||
      lr.mean_shift > lr.shift || (third & ~(kMeanShiftMask | kCoeffShifts | kPosed | kPackedDifferences)) != 0 ||
      (packed && (ranged || !fast_format)))
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
  const bool read = packed   ? read_packed_differences(r, count, K, &lr.coeffs, store)
                    : ranged ? decode_differences(r, count, K, !lr.coeff_shifts.empty(), &lr.coeffs, store)
                             : read_varint_differences(r, count, K, &lr.coeffs, store);
  if (!read) return false;
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
    if (!(packed ? read_packed_differences(r, values, kLowRankPoseValues, &lr.poses, store_pose)
                 : decode_differences(r, values, kLowRankPoseValues, true, &lr.poses, store_pose)))
      return false;
  }
  return r.ok;
}

}  // namespace dcurve
