#include "codec/compress/low_rank_writer.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/fast_residual.h"
#include "codec/common/int_coder.h"
#include "codec/common/low_rank.h"
#include "codec/common/low_rank_format.h"
#include "codec/compress/range_encoder.h"
#include "codec/compress/zstd_frame_writer.h"

namespace dcurve {
namespace {
using low_rank_format::coeff_context;
using low_rank_format::difference;
using low_rank_format::kCoeffContexts;
using low_rank_format::kCoeffShifts;
using low_rank_format::kPackedDifferences;
using low_rank_format::kPosed;
using low_rank_format::kRangeCoded;
using low_rank_format::range_count_plausible;

std::vector<uint8_t> range_coded_differences(const std::vector<int32_t>& stored, size_t K, bool contexts) {
  RangeEncoder enc;
  AdaptiveIntCoder coder(contexts ? kCoeffContexts : 1, 1);
  for (size_t i = 0; i < stored.size(); ++i)
    coder.encode(enc, contexts ? coeff_context(stored, i, K) : 0, 0, difference(stored, i, K));
  return enc.finish();
}

ByteWriter varint_differences(const std::vector<int32_t>& stored, size_t K) {
  ByteWriter varints;
  for (size_t i = 0; i < stored.size(); ++i) varints.varint(zigzag_encode(difference(stored, i, K)));
  return varints;
}

// The packed form (kPackedDifferences) of the svarints `varints`: their size, then one zstd
// frame of them.
void put_packed(const ByteWriter& varints, ByteWriter* w) {
  const std::vector<uint8_t> packed = zstd_frame(varints.data(), 19);
  w->varint(varints.size());
  w->varint(packed.size());
  w->bytes(packed.data(), packed.size());
}

// Format 4 files (a fast residual payload) pack their differences: decode speed over bytes.
bool packs_differences(const Model& m) {
  return !m.residual.payload.empty() && m.residual.payload[0] == fast_residual::kPayloadVersion;
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
  // Packed (format 4), else svarints or the adaptive range coder, whichever is smaller: the
  // differences of one file have similar magnitudes, which a varint's fixed 7-bit groups do
  // not exploit.
  const bool packed = packs_differences(m);
  const ByteWriter varints = varint_differences(stored, K);
  const std::vector<uint8_t> stream = packed ? std::vector<uint8_t>{} : range_coded_differences(stored, K, shifted);
  ByteWriter sized;
  sized.varint(stream.size());
  const bool ranged = !packed && range_count_plausible(stored.size(), stream.size()) &&
                      sized.size() + stream.size() < varints.size();
  ByteWriter w;
  w.u8(uint8_t(lr.components | (ranged ? kRangeCoded : 0)));
  w.u8(uint8_t(lr.shift));
  const bool posed = !lr.poses.empty();
  w.u8(uint8_t(lr.mean_shift | (shifted ? kCoeffShifts : 0) | (posed ? kPosed : 0) | (packed ? kPackedDifferences : 0)));
  if (shifted)
    for (uint8_t s : lr.coeff_shifts) w.u8(s);
  if (packed) {
    put_packed(varints, &w);
  } else if (ranged) {
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
    if (packed) {
      put_packed(varint_differences(lr.poses, kLowRankPoseValues), &w);
    } else {
      const std::vector<uint8_t> poses = range_coded_differences(lr.poses, kLowRankPoseValues, true);
      w.varint(poses.size());
      w.bytes(poses.data(), poses.size());
    }
  }
  return std::move(w.data());
}

}  // namespace dcurve
