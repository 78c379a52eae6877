#include "codec/compress/faces_compact_encoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/faces_compact_walk.h"
#include "codec/compress/range_encoder.h"

namespace dcurve {
namespace {

using faces_compact_walk::traverse;
using faces_compact_walk::triangle_bound;

// The encoder's Io of the traversal (codec/common/faces_compact_walk.h): codes the decision
// it is given and returns it.
struct EncodeIo {
  static constexpr bool kDecoding = false;
  int bit(BitModel& m, int b) {
    enc.encode(m, b);
    return b;
  }
  int64_t integer(AdaptiveIntCoder& c, int ctx, int sign_ctx, int64_t v) {
    c.encode(enc, ctx, sign_ctx, v);
    return v;
  }
  bool overrun() const { return false; }
  RangeEncoder enc;
};

}  // namespace

bool encode_compact_faces(const std::vector<uint32_t>& faces, std::vector<uint8_t>* out) {
  const uint64_t T = faces.size() / 3;
  std::vector<uint32_t> list(faces.begin(), faces.begin() + ptrdiff_t(3 * T));
  EncodeIo io;
  const uint32_t bound = list.empty() ? 0 : *std::max_element(list.begin(), list.end()) + 1;  // ids <= 2^32 - 2
  if (bound > kCompactFreeIds + kCompactIdsPerTriangle * T) return false;
  traverse(io, T, bound, &list, nullptr);
  const std::vector<uint8_t>& stream = io.enc.finish();
  if (T > triangle_bound(stream.size())) return false;
  ByteWriter w;
  w.varint(T);
  w.bytes(stream.data(), stream.size());
  out->insert(out->end(), w.data().begin(), w.data().end());
  return true;
}

}  // namespace dcurve
