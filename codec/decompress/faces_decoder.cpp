#include "codec/decompress/faces_decoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/error.h"
#include "codec/common/faces_exact.h"
#include "codec/decompress/faces_compact_decoder.h"

namespace dcurve {
namespace {

using faces_exact::History;
using faces_exact::kOpHasEdge;
using faces_exact::kOpThirdIsNext;

// Leaves *faces as it stops on bad input: decode_faces clears it on any failure.
bool decode_exact(ByteReader& r, std::vector<uint32_t>* faces, std::string* error) {
  uint64_t T = r.varint();
  // One op byte per triangle: the count can never exceed the bytes that follow.
  if (!r.ok || T > r.remaining()) return fail(error, "face count exceeds the section size");
  const uint8_t* ops = r.take(size_t(T));
  faces->resize(size_t(T) * 3);
  History h;
  int64_t ref = 0;
  auto explicit_id = [&](uint32_t* out) {
    int64_t v = 0;
    if (!add_zigzag_delta(ref, r.varint(), &v) || !r.ok || v < 0 || v >= int64_t(UINT32_MAX)) return false;
    *out = uint32_t(v);
    ref = v;
    return true;
  };
  for (size_t t = 0; t < T; ++t) {
    uint8_t op = ops[t];
    uint32_t* tri = &(*faces)[3 * t];
    if (op & kOpHasEdge) {
      int k = (op >> 3) & 15, rot = op & 3;
      if (k >= h.filled || rot > 2) return fail(error, "face op refers to an edge or rotation that does not exist");
      uint32_t canon[3] = {h.edge(k)[0], h.edge(k)[1], 0};
      if (op & kOpThirdIsNext) {
        if (h.next >= UINT32_MAX) return fail(error, "face vertex id overflows");
        canon[2] = uint32_t(h.next);
      } else if (!explicit_id(&canon[2])) {
        return fail(error, "face vertex id is truncated or out of range");
      }
      for (int c = 0; c < 3; ++c) tri[(rot + c) % 3] = canon[c];
    } else {
      if (op & 0x78) return fail(error, "face op has reserved bits set");
      uint64_t next = h.next;
      for (int c = 0; c < 3; ++c) {
        if (op & (1 << c)) {
          if (next >= UINT32_MAX) return fail(error, "face vertex id overflows");
          tri[c] = uint32_t(next);
        } else if (!explicit_id(&tri[c])) {
          return fail(error, "face vertex id is truncated or out of range");
        }
        next = std::max<uint64_t>(next, uint64_t(tri[c]) + 1);
      }
    }
    h.add(tri);
  }
  return true;
}

// As decode_exact: decode_faces clears *faces on failure.
bool decode_traversal(ByteReader& r, std::vector<uint32_t>* faces, std::string* error) {
  const uint64_t T = r.varint();
  const uint64_t S = r.varint();
  // Every triangle costs at least one byte of ids: the count is bounded by the section.
  if (!r.ok || T > r.remaining() || S > r.remaining()) return fail(error, "face count exceeds the section size");
  const uint8_t* symbols = r.take(size_t(S));
  faces->clear();
  faces->reserve(size_t(T) * 3);
  int64_t ref = 0;
  size_t head = 0, s = 0;
  auto id = [&](int64_t base, uint32_t* out) {
    int64_t v = 0;
    if (!add_zigzag_delta(base, r.varint(), &v) || !r.ok || v < 0 || v >= int64_t(UINT32_MAX)) return false;
    *out = uint32_t(v);
    return true;
  };
  while (faces->size() < T * 3) {
    if (head * 3 == faces->size()) {
      for (int c = 0; c < 3; ++c) {
        uint32_t v;
        if (!id(ref, &v)) return fail(error, "face vertex id is truncated or out of range");
        ref = v;
        faces->push_back(v);
      }
    }
    for (int e = 0; e < 3 && faces->size() < T * 3; ++e) {
      if (s >= S) return fail(error, "face traversal symbols are truncated");
      const uint8_t sym = symbols[s++];
      if (sym > 1) return fail(error, "face traversal symbol is not 0 or 1");
      if (!sym) continue;
      const uint32_t a = (*faces)[3 * head + e], b = (*faces)[3 * head + (e + 1) % 3];
      uint32_t x;
      if (!id(a, &x)) return fail(error, "face vertex id is truncated or out of range");
      faces->insert(faces->end(), {b, a, x});
    }
    ++head;
  }
  if (s != S) return fail(error, "face traversal has unused symbols");
  return true;
}

}  // namespace

bool decode_faces(const uint8_t* bytes, size_t size, uint32_t vertex_count, std::vector<uint32_t>* faces,
                  std::string* error) {
  ByteReader r(bytes, size);
  const uint8_t layout = r.u8();
  std::string why;
  bool ok = false;
  if (!r.ok) why = "face section is empty";
  else if (layout == uint8_t(FaceOrder::Exact)) ok = decode_exact(r, faces, &why);
  else if (layout == uint8_t(FaceOrder::Traversal)) ok = decode_traversal(r, faces, &why);
  else if (layout == uint8_t(FaceOrder::Compact)) {
    // The range-coded stream runs to the end of the payload.
    ok = decode_compact_faces(bytes + r.position(), r.remaining(), vertex_count, faces, &why);
    r.take(r.remaining());
  }
  else why = "unknown face layout " + std::to_string(layout);
  if (ok && r.remaining() != 0) ok = false, why = "face section has trailing bytes";
  if (!ok) {
    faces->clear();
    if (error) *error = why;
  }
  return ok;
}

}  // namespace dcurve
