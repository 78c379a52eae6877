// The vertex order and spatial predictors of the fast payload (format 4,
// format_spec/residual.md section 10.4), derived from the triangle list alone in one pass:
// each vertex is predicted from vertices met before it, by parallelogram where an earlier
// triangle lies across the edge it is reached from. Encoder and decoder derive it alike.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dcurve {

enum class FastSpatial : uint8_t { None = 0, Copy = 1, Mean = 2, Parallelogram = 3 };

struct FastTraversal {
  std::vector<uint32_t> order;   // position -> vertex id, a permutation of [0, V)
  std::vector<uint8_t> type;     // per position, a FastSpatial
  // Per position 3 earlier positions (a, b, c): Copy a; Mean (a, b); a + b - c. Positions, not
  // vertex ids, so a frame's corrections are read in traversal order: the references of a
  // position are mostly a few steps back, in cache.
  std::vector<uint32_t> refs;
  size_t bytes() const { return order.capacity() * 4 + type.capacity() + refs.capacity() * 4; }
};

// From `faces` (3 vertex ids < V each, in file order). Without faces: vertex id order, each
// vertex a copy of the one before.
FastTraversal fast_traversal(const std::vector<uint32_t>& faces, uint32_t V);

// The spatial prediction of the vertex at position i from the values e (position-major, 3
// per position) of the positions before it, axis a. smooth: Mean where the type is Parallelogram
// (a noisy field, e.g. rounding left by a model, is predicted better by an average).
inline int64_t fast_spatial(const FastTraversal& t, size_t i, const int64_t* e, int a, bool smooth = false) {
  const uint32_t* r = &t.refs[i * 3];
  const FastSpatial type = FastSpatial(t.type[i]);
  switch (smooth && type == FastSpatial::Parallelogram ? FastSpatial::Mean : type) {
    case FastSpatial::Copy: return e[size_t(r[0]) * 3 + size_t(a)];
    case FastSpatial::Mean: return (e[size_t(r[0]) * 3 + size_t(a)] + e[size_t(r[1]) * 3 + size_t(a)] + 1) >> 1;
    case FastSpatial::Parallelogram:
      return e[size_t(r[0]) * 3 + size_t(a)] + e[size_t(r[1]) * 3 + size_t(a)] - e[size_t(r[2]) * 3 + size_t(a)];
    default: return 0;
  }
}

}  // namespace dcurve
