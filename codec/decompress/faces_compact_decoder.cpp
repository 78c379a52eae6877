#include "codec/decompress/faces_compact_decoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/error.h"
#include "codec/common/faces_compact_walk.h"
#include "codec/decompress/range_decoder.h"

namespace dcurve {
namespace {

using faces_compact_walk::traverse;
using faces_compact_walk::triangle_bound;

// The decoder's Io of the traversal (codec/common/faces_compact_walk.h): ignores the
// decision it is given and returns what the stream says.
struct DecodeIo {
  static constexpr bool kDecoding = true;
  DecodeIo(const uint8_t* data, size_t size) : dec(data, size) {}
  int bit(BitModel& m, int) { return dec.decode(m); }
  int64_t integer(AdaptiveIntCoder& c, int ctx, int sign_ctx, int64_t) { return c.decode(dec, ctx, sign_ctx); }
  bool overrun() const { return dec.overrun(); }
  RangeDecoder dec;
};

}  // namespace

bool decode_compact_faces(const uint8_t* data, size_t size, uint32_t vertex_count, std::vector<uint32_t>* faces,
                          std::string* error) {
  ByteReader r(data, size);
  const uint64_t T = r.varint();
  if (!r.ok) return fail(error, "face count is truncated");
  if (T > triangle_bound(r.remaining())) return fail(error, "face count exceeds what the section can hold");
  DecodeIo io(data + r.position(), r.remaining());
  faces->clear();
  faces->reserve(size_t(std::min<uint64_t>(T, 1u << 20)) * 3);
  if (!traverse(io, T, vertex_count, faces, error)) return false;
  if (!io.dec.at_clean_end()) return fail(error, "face stream is truncated or has corrupt trailing bytes");
  return true;
}

}  // namespace dcurve
