// What the writer (codec/compress/low_rank_writer.cpp) and the reader
// (codec/decompress/low_rank_reader.cpp) of the LRNK payload share: its flag bits and the
// extrapolation and contexts the coefficient differences are coded with
// (format_spec/dcrv.md section 10).
#pragma once
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace dcurve {
namespace low_rank_format {

// Coefficients follow smooth trajectories: coefficient i (frame-major, K per frame) is
// predicted by linear extrapolation from the same component's two previous frames
// (constant from one, 0 for frame 0), and only the difference is written.
inline int64_t predicted_coeff(const std::vector<int32_t>& c, size_t i, size_t K) {
  if (i >= 2 * K) return 2 * int64_t(c[i - K]) - int64_t(c[i - 2 * K]);
  return i >= K ? int64_t(c[i - K]) : 0;
}

// Bit 7 of the component byte: the differences are range-coded (format 2.1), not svarints.
constexpr uint8_t kRangeCoded = 0x80;
// Bit 7 of the mean-shift byte: K per-component coefficient shifts follow (format 2.3).
constexpr uint8_t kCoeffShifts = 0x80;
// Bit 6 of the mean-shift byte: frame poses follow the basis payload (format 2.5). The mean
// shift itself needs bits 0-4 (at most 30).
constexpr uint8_t kPosed = 0x40;
// Bit 5 of the mean-shift byte (format 4 only): the coefficient and pose differences are
// svarints in one zstd frame each, not range-coded: static tables, so a decoder opens a long
// clip without an adaptive decode of every coefficient.
constexpr uint8_t kPackedDifferences = 0x20;
constexpr uint8_t kMeanShiftMask = 0x1f;
// A packed stream's svarints: at least one byte each, at most 6 (|difference| <= 2^40).
constexpr uint64_t kMaxSvarintBytes = 6;

// A range-coded stream may hold many values per byte; a decoder allocates F * K values only
// when F * K <= 4096 + 64 * stream bytes (the writer keeps svarints beyond that).
inline bool range_count_plausible(uint64_t count, uint64_t stream_bytes) { return count <= 4096 + 64 * stream_bytes; }

inline int64_t difference(const std::vector<int32_t>& c, size_t i, size_t K) {
  return int64_t(c[i]) - predicted_coeff(c, i, K);
}

// Magnitude context of stored coefficient i with per-component shifts (2.3): the class of the
// same component's difference one frame earlier (6 for frame 0). Shifted components differ in
// magnitude by orders, which one shared context averages away.
constexpr int kCoeffContexts = 7;
inline int coeff_context(const std::vector<int32_t>& c, size_t i, size_t K) {
  if (i < K) return 6;
  const uint64_t m = uint64_t(std::abs(difference(c, i - K, K)));
  return m == 0 ? 0 : m == 1 ? 1 : m < 4 ? 2 : m < 16 ? 3 : m < 256 ? 4 : 5;
}

}  // namespace low_rank_format
}  // namespace dcurve
