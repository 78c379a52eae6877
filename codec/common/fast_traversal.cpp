#include "codec/common/fast_traversal.h"

namespace dcurve {
namespace {

// Undirected edge -> the third vertex of the first triangle that has it. Open addressing:
// a decoder builds this at open, and std::unordered_map's node allocations cost it more
// than the rest of the pass.
class EdgeTable {
 public:
  explicit EdgeTable(size_t edges) {
    size_t cap = 16;
    while (cap < 2 * edges) cap *= 2;
    keys_.assign(cap, kEmpty);
    values_.resize(cap);
  }
  // The stored opposite of edge (x, y), or UINT32_MAX.
  uint32_t find(uint32_t x, uint32_t y) const {
    const uint64_t k = key(x, y);
    for (size_t s = slot(k);; s = (s + 1) & (keys_.size() - 1)) {
      if (keys_[s] == k) return values_[s];
      if (keys_[s] == kEmpty) return UINT32_MAX;
    }
  }
  // Stores w as the opposite of (x, y) unless the edge has one.
  void insert(uint32_t x, uint32_t y, uint32_t w) {
    const uint64_t k = key(x, y);
    size_t s = slot(k);
    while (keys_[s] != kEmpty && keys_[s] != k) s = (s + 1) & (keys_.size() - 1);
    if (keys_[s] == kEmpty) {
      keys_[s] = k;
      values_[s] = w;
    }
  }

 private:
  static constexpr uint64_t kEmpty = UINT64_MAX;  // no edge of vertex ids < 2^32 - 1 has this key
  static uint64_t key(uint32_t x, uint32_t y) { return x < y ? uint64_t(x) << 32 | y : uint64_t(y) << 32 | x; }
  size_t slot(uint64_t k) const { return size_t((k * 0x9E3779B97F4A7C15ull) >> 20) & (keys_.size() - 1); }
  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
};

struct Builder {
  FastTraversal t;
  std::vector<uint32_t> position;  // per vertex, UINT32_MAX until seen
  bool seen(uint32_t v) const { return position[v] != UINT32_MAX; }
  // Vertex v at the next position, predicted from the vertices a, b, c (seen ones, or 0 where
  // the type reads none).
  void add(uint32_t v, FastSpatial type, uint32_t a, uint32_t b, uint32_t c) {
    position[v] = uint32_t(t.order.size());
    t.order.push_back(v);
    t.type.push_back(uint8_t(type));
    const int used = type == FastSpatial::Parallelogram ? 3 : int(type);
    t.refs.insert(t.refs.end(), {used > 0 ? position[a] : 0, used > 1 ? position[b] : 0, used > 2 ? position[c] : 0});
  }
  // Corner x of a triangle whose other corners are y, z: predicted from what is seen of them.
  void reach(uint32_t x, uint32_t y, uint32_t z, const EdgeTable& edges) {
    if (seen(x)) return;
    if (seen(y) && seen(z)) {
      const uint32_t w = edges.find(y, z);
      if (w != UINT32_MAX) add(x, FastSpatial::Parallelogram, y, z, w);
      else add(x, FastSpatial::Mean, y, z, 0);
    } else if (seen(y) || seen(z)) {
      add(x, FastSpatial::Copy, seen(y) ? y : z, 0, 0);
    } else {
      add(x, FastSpatial::None, 0, 0, 0);
    }
  }
};
}  // namespace

FastTraversal fast_traversal(const std::vector<uint32_t>& faces, uint32_t V) {
  Builder b;
  b.position.assign(V, UINT32_MAX);
  b.t.order.reserve(V);
  b.t.type.reserve(V);
  b.t.refs.reserve(size_t(V) * 3);
  EdgeTable edges(faces.size());
  for (size_t k = 0; k + 2 < faces.size(); k += 3) {
    const uint32_t x = faces[k], y = faces[k + 1], z = faces[k + 2];
    b.reach(x, y, z, edges);
    b.reach(y, z, x, edges);
    b.reach(z, x, y, edges);
    edges.insert(x, y, z);
    edges.insert(y, z, x);
    edges.insert(z, x, y);
  }
  for (uint32_t v = 0; v < V; ++v)
    if (!b.seen(v)) {
      const bool first = b.t.order.empty();
      b.add(v, first ? FastSpatial::None : FastSpatial::Copy, first ? 0 : b.t.order.back(), 0, 0);
    }
  return std::move(b.t);
}

}  // namespace dcurve
