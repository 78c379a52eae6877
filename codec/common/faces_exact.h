// What the writer and the reader of the FACE Exact layout share (codec/compress/faces_encoder.cpp,
// codec/decompress/faces_decoder.cpp): the op byte's flags and the edge history both keep.
#pragma once
#include <algorithm>
#include <cstdint>

namespace dcurve {
namespace faces_exact {

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

}  // namespace faces_exact
}  // namespace dcurve
