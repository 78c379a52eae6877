#include "codec/faces.h"

#include <algorithm>

#include "codec/bytes.h"
#include "codec/error.h"
#include "codec/faces_compact.h"

namespace dcurve {
namespace {

// Both sides keep the same small history: the 16 most recent directed edges (as a
// neighbouring, consistently oriented triangle would list them) and the next never-seen
// vertex id. A triangle that shares an edge with a recent one costs one op byte, plus
// nothing when its third corner is a new vertex: that is why this beats delta coding.
constexpr int kEdgeFifo = 16;
constexpr uint8_t kOpHasEdge = 0x80;
constexpr uint8_t kOpThirdIsNext = 0x04;

struct History {
  uint32_t edges[kEdgeFifo][2] = {};
  int head = 0;       // slot of the most recent edge
  int filled = 0;
  uint64_t next = 0;  // 1 + the largest id seen so far

  // Edge k steps back (k = 0 is the most recent).
  const uint32_t* edge(int k) const { return edges[(head - k + kEdgeFifo) % kEdgeFifo]; }
  void push_edge(uint32_t from, uint32_t to) {
    head = (head + 1) % kEdgeFifo;
    edges[head][0] = from;
    edges[head][1] = to;
    filled = std::min(filled + 1, kEdgeFifo);
  }
  void add(const uint32_t* tri) {
    push_edge(tri[1], tri[0]);
    push_edge(tri[2], tri[1]);
    push_edge(tri[0], tri[2]);
    for (int k = 0; k < 3; ++k) next = std::max<uint64_t>(next, uint64_t(tri[k]) + 1);
  }
};


// Exact layout: one op byte per triangle against a short edge history, then explicit ids.
std::vector<uint8_t> encode_exact(const std::vector<uint32_t>& faces) {
  const size_t T = faces.size() / 3;
  ByteWriter head, data;
  head.u8(uint8_t(FaceOrder::Exact));
  head.varint(T);
  std::vector<uint8_t> ops(T);
  History h;
  int64_t ref = 0;  // the last explicitly coded id: explicit ids are coded as a delta to it
  auto explicit_id = [&](uint32_t v) {
    data.varint(zigzag_encode(int64_t(v) - ref));
    ref = v;
  };
  for (size_t t = 0; t < T; ++t) {
    const uint32_t* tri = &faces[3 * t];
    int hit_edge = -1, hit_rot = 0;
    for (int k = 0; k < h.filled && hit_edge < 0; ++k)
      for (int r = 0; r < 3; ++r)
        if (h.edge(k)[0] == tri[r] && h.edge(k)[1] == tri[(r + 1) % 3]) {
          hit_edge = k;
          hit_rot = r;
          break;
        }
    uint8_t op = 0;
    if (hit_edge >= 0) {
      uint32_t third = tri[(hit_rot + 2) % 3];
      op = uint8_t(kOpHasEdge | hit_edge << 3 | hit_rot);
      if (third == h.next) op |= kOpThirdIsNext;
      else explicit_id(third);
    } else {
      uint64_t next = h.next;
      for (int k = 0; k < 3; ++k) {
        if (tri[k] == next) op |= uint8_t(1 << k);
        else explicit_id(tri[k]);
        next = std::max<uint64_t>(next, uint64_t(tri[k]) + 1);
      }
    }
    ops[t] = op;
    h.add(tri);
  }
  head.bytes(ops.data(), ops.size());
  head.bytes(data.data().data(), data.size());
  return std::move(head.data());
}

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

// Traversal layout. Triangles are emitted in breadth-first order: the queue is the output
// list itself. For each queued triangle (a, b, c) and each of its edges (a,b), (b,c), (c,a)
// in turn, one symbol says whether the not-yet-emitted triangle across that edge follows,
// as (b, a, x) with x coded as a delta to a. When the queue runs dry a new component starts
// with three explicit ids. Processing stops the moment all triangles are out.
std::vector<uint8_t> encode_traversal(const std::vector<uint32_t>& faces) {
  const size_t T = faces.size() / 3;
  // Every corner as (directed edge it starts, third corner, triangle * 3 + corner), sorted:
  // where several triangles share a directed edge (non-manifold or repeated triangles), the
  // one with the smallest third corner follows, a choice that does not depend on the list
  // order and so makes traversal_order a fixed point.
  struct Corner {
    uint64_t edge;
    uint32_t third, at;
    bool operator<(const Corner& o) const {
      return edge != o.edge ? edge < o.edge : third != o.third ? third < o.third : at < o.at;
    }
  };
  std::vector<Corner> by_edge;
  by_edge.reserve(faces.size());
  for (size_t t = 0; t < T; ++t)
    for (int c = 0; c < 3; ++c)
      by_edge.push_back({uint64_t(faces[3 * t + c]) << 32 | faces[3 * t + (c + 1) % 3],
                         faces[3 * t + (c + 2) % 3], uint32_t(3 * t + c)});
  std::sort(by_edge.begin(), by_edge.end());
  std::vector<uint8_t> done(T, 0), symbols;
  std::vector<uint32_t> out;
  out.reserve(faces.size());
  ByteWriter ids;
  int64_t ref = 0;
  size_t head = 0, next_start = 0;
  while (out.size() < faces.size()) {
    if (head * 3 == out.size()) {
      while (done[next_start]) ++next_start;
      done[next_start] = 1;
      for (int c = 0; c < 3; ++c) {
        uint32_t v = faces[3 * next_start + c];
        ids.varint(zigzag_encode(int64_t(v) - ref));
        ref = v;
        out.push_back(v);
      }
    }
    for (int e = 0; e < 3 && out.size() < faces.size(); ++e) {
      const uint32_t a = out[3 * head + e], b = out[3 * head + (e + 1) % 3];
      const uint64_t key = uint64_t(b) << 32 | a;
      auto it = std::lower_bound(by_edge.begin(), by_edge.end(), Corner{key, 0, 0});
      while (it != by_edge.end() && it->edge == key && done[it->at / 3]) ++it;
      if (it == by_edge.end() || it->edge != key) {
        symbols.push_back(0);
        continue;
      }
      done[it->at / 3] = 1;
      const uint32_t x = it->third;
      symbols.push_back(1);
      ids.varint(zigzag_encode(int64_t(x) - int64_t(a)));
      out.insert(out.end(), {b, a, x});
    }
    ++head;
  }
  ByteWriter w;
  w.u8(uint8_t(FaceOrder::Traversal));
  w.varint(T);
  w.varint(symbols.size());
  w.bytes(symbols.data(), symbols.size());
  w.bytes(ids.data().data(), ids.size());
  return std::move(w.data());
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

std::vector<uint8_t> encode_faces(const std::vector<uint32_t>& faces, FaceOrder order) {
  if (order == FaceOrder::Traversal) return encode_traversal(faces);
  if (order == FaceOrder::Compact) {
    std::vector<uint8_t> out{uint8_t(FaceOrder::Compact)};
    if (encode_compact_faces(faces, &out)) return out;
  }
  return encode_exact(faces);
}

std::vector<uint32_t> traversal_order(const std::vector<uint32_t>& faces) {
  std::vector<uint8_t> bytes = encode_traversal(faces);
  std::vector<uint32_t> out;
  decode_faces(bytes.data(), bytes.size(), &out, nullptr);
  return out;
}

bool decode_faces(const uint8_t* bytes, size_t size, std::vector<uint32_t>* faces, std::string* error) {
  ByteReader r(bytes, size);
  const uint8_t layout = r.u8();
  std::string why;
  bool ok = false;
  if (!r.ok) why = "face section is empty";
  else if (layout == uint8_t(FaceOrder::Exact)) ok = decode_exact(r, faces, &why);
  else if (layout == uint8_t(FaceOrder::Traversal)) ok = decode_traversal(r, faces, &why);
  else if (layout == uint8_t(FaceOrder::Compact)) {
    // The range-coded stream runs to the end of the payload.
    ok = decode_compact_faces(bytes + r.position(), r.remaining(), faces, &why);
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
