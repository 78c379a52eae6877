#include "codec/compress/faces_encoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/faces_exact.h"
#include "codec/compress/faces_compact_encoder.h"

namespace dcurve {
namespace {

using faces_exact::History;
using faces_exact::kOpHasEdge;
using faces_exact::kOpThirdIsNext;

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

// Traversal layout. Triangles are emitted in breadth-first order: the queue is the output
// list itself. For each queued triangle (a, b, c) and each of its edges (a,b), (b,c), (c,a)
// in turn, one symbol says whether the not-yet-emitted triangle across that edge follows,
// as (b, a, x) with x coded as a delta to a. When the queue runs dry a new component starts
// with three explicit ids. Processing stops the moment all triangles are out. *order gets
// the emitted list: what a reader decodes.
std::vector<uint8_t> encode_traversal(const std::vector<uint32_t>& faces, std::vector<uint32_t>* order) {
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
  std::vector<uint32_t>& out = *order;
  out.clear();
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

}  // namespace

std::vector<uint8_t> encode_faces(const std::vector<uint32_t>& faces, FaceOrder order,
                                  std::vector<uint32_t>* traversal) {
  if (order == FaceOrder::Traversal) {
    std::vector<uint32_t> unused;
    return encode_traversal(faces, traversal ? traversal : &unused);
  }
  if (order == FaceOrder::Compact) {
    std::vector<uint8_t> out{uint8_t(FaceOrder::Compact)};
    if (encode_compact_faces(faces, &out)) return out;
  }
  return encode_exact(faces);
}

std::vector<uint32_t> traversal_order(const std::vector<uint32_t>& faces) {
  std::vector<uint32_t> out;
  encode_traversal(faces, &out);
  return out;
}

}  // namespace dcurve
