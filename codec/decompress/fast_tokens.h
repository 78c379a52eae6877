// The op and value tokens of a fast residual frame (format_spec/residual.md section 10.3), as
// every reader of a fast chunk walks them: one frame at a time, or several side by side.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/bytes.h"  // zigzag_decode
#include "codec/common/fast_residual.h"

namespace dcurve {
namespace fast_tokens {

// A value token at values[*pos]: false when it does not end before `end` or the escape is
// malformed.
inline bool read_value(const uint8_t* values, size_t end, size_t* pos, int64_t* r) {
  if (*pos >= end) return false;
  const uint8_t c = values[(*pos)++];
  if (c != fast_residual::kValueEscape) {
    *r = zigzag_decode(uint64_t(c) + 1);
    return true;
  }
  uint64_t u = 0;
  for (int shift = 0;; shift += 7) {
    if (shift > 35 || *pos >= end) return false;  // |r| < 2^32 needs at most 5 bytes
    const uint8_t b = values[(*pos)++];
    u |= uint64_t(b & 0x7f) << shift;
    if (!(b & 0x80)) break;
  }
  *r = zigzag_decode(u + 256);
  return true;
}

inline bool in_int32(int64_t v) { return v >= INT32_MIN && v <= INT32_MAX; }

// One frame's op bytes, read one slot with non-zero residuals at a time: a slot is a vertex
// id, or with the spatial flag a traversal position.
struct OpCursor {
  const std::vector<uint8_t>& ops;
  size_t pos, end;
  uint32_t V;
  uint32_t cursor = 0, slot = 0;
  uint8_t mask = 0;
  // The next such slot and its axis mask; slot = V after the frame's last op. False on an op
  // that passes the last slot.
  bool next() {
    using fast_residual::kLongSkip;
    while (pos < end) {
      const uint8_t b = ops[pos++];
      const uint32_t m = b & 7, s = b >> 3;
      cursor += m == 0 ? kLongSkip * (s + 1) : s;
      if (cursor >= V) return false;
      if (m == 0) continue;
      slot = cursor++;
      mask = uint8_t(m);
      return true;
    }
    slot = V;
    mask = 0;
    return true;
  }
};

// The number of value tokens the op bytes ops[begin, end) call for.
inline uint64_t value_count(const uint8_t* ops, size_t begin, size_t end) {
  static constexpr uint8_t kBits[8] = {0, 1, 1, 2, 1, 2, 2, 3};
  uint64_t n = 0;
  for (size_t i = begin; i < end; ++i) n += kBits[ops[i] & 7];
  return n;
}

// Past one frame's tokens: its `op_count` op bytes at *op_pos, and the value tokens they call
// for at *value_pos, stepped over byte by byte (an escaped value takes more than one). False
// when the values end first.
inline bool skip_frame_tokens(const std::vector<uint8_t>& ops, const std::vector<uint8_t>& values, uint32_t op_count,
                              size_t* op_pos, size_t* value_pos) {
  const size_t end = *op_pos + op_count;
  int64_t r = 0;
  for (uint64_t n = value_count(ops.data(), *op_pos, end); n > 0; --n)
    if (!read_value(values.data(), values.size(), value_pos, &r)) return false;
  *op_pos = end;
  return true;
}

// Where each of `count` frames' tokens start: ops at op_begin, values at value_begin (and the
// frame after the last at [count]).
struct FrameTokens {
  std::vector<size_t> op_begin, value_begin;
};

// FrameTokens of frames first .. first + count - 1, their tokens starting at op_pos and
// value_pos. False when the values end first.
inline bool token_starts(const std::vector<uint8_t>& ops, const std::vector<uint8_t>& values,
                         const std::vector<uint32_t>& op_counts, uint32_t first, uint32_t count, size_t op_pos,
                         size_t value_pos, FrameTokens* t) {
  for (uint32_t j = 0; j <= count; ++j) {
    t->op_begin.push_back(op_pos);
    t->value_begin.push_back(value_pos);
    if (j < count && !skip_frame_tokens(ops, values, op_counts[first + j], &op_pos, &value_pos)) return false;
  }
  return true;
}

}  // namespace fast_tokens
}  // namespace dcurve
