#include "codec/common/fast_traversal.h"

#include "codec/common/flat_index.h"

namespace dcurve {
namespace {

// Undirected edge (x, y) as a FlatIndex key: the table maps it to the third vertex of the
// first triangle that has it.
uint64_t undirected(uint32_t x, uint32_t y) { return x < y ? uint64_t(x) << 32 | y : uint64_t(y) << 32 | x; }

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
  void reach(uint32_t x, uint32_t y, uint32_t z, const FlatIndex& edges) {
    if (seen(x)) return;
    if (seen(y) && seen(z)) {
      const uint32_t w = edges.find(undirected(y, z));
      if (w != FlatIndex::kMissing) add(x, FastSpatial::Parallelogram, y, z, w);
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
  FlatIndex edges;
  edges.reserve(faces.size() / 2);  // a closed mesh's edges; an open one grows once or twice
  for (size_t k = 0; k + 2 < faces.size(); k += 3) {
    const uint32_t x = faces[k], y = faces[k + 1], z = faces[k + 2];
    b.reach(x, y, z, edges);
    b.reach(y, z, x, edges);
    b.reach(z, x, y, edges);
    edges.insert(undirected(x, y), z);  // the first triangle met keeps an edge
    edges.insert(undirected(y, z), x);
    edges.insert(undirected(z, x), y);
  }
  for (uint32_t v = 0; v < V; ++v)
    if (!b.seen(v)) {
      const bool first = b.t.order.empty();
      b.add(v, first ? FastSpatial::None : FastSpatial::Copy, first ? 0 : b.t.order.back(), 0, 0);
    }
  return std::move(b.t);
}

}  // namespace dcurve
