#include "codec/common/model.h"

namespace dcurve {

Curves singleton_curves(uint32_t V) {
  Curves c;
  c.vertices.resize(V);
  c.offsets.resize(size_t(V) + 1);
  c.closed.assign(V, 0);
  c.u.assign(V, 0.f);
  for (uint32_t v = 0; v < V; ++v) c.vertices[v] = c.offsets[v] = v;
  c.offsets[V] = V;
  return c;
}

bool is_singleton_curves(const Curves& c, uint32_t V) {
  if (c.curve_count() != V || c.vertices.size() != V || c.u.size() != V || c.closed.size() != V) return false;
  for (uint32_t v = 0; v < V; ++v)
    if (c.vertices[v] != v || c.offsets[v] != v || c.closed[v] != 0 || c.u[v] != 0.f) return false;
  return c.offsets[V] == V;
}

}  // namespace dcurve
