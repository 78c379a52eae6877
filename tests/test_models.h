// Small deterministic models shared by the container, decoder and test-vector tests. Every
// value comes from a closed formula, so expected positions are computed here, independently
// of the decoder.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/model.h"
#include "codec/residual.h"

namespace dcurve::testing {

// Grid value of frame f, vertex v, axis a: smooth in f with a vertex- and axis-dependent
// offset, negative values included.
inline int32_t grid_value(uint32_t f, uint32_t v, int a) {
  return int32_t(v * 7 + a * 3) - 9 + int32_t(f * f) * (a + 1) - int32_t(f * v % 5);
}

inline std::vector<int32_t> grid(uint32_t V, uint32_t F) {
  std::vector<int32_t> q(size_t(V) * F * 3);
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t v = 0; v < V; ++v)
      for (int a = 0; a < 3; ++a) q[(size_t(f) * V + v) * 3 + a] = grid_value(f, v, a);
  return q;
}

// Two curves over 6 vertices (one open, one closed, ids shuffled), 4 triangles, F frames,
// and the residual layer holding grid(). `segment_frames` lists segment boundaries, e.g.
// {0, 2, F-1}; empty means no segments. Motions are all Basis::Zero.
inline Model small_model(uint32_t F, const std::vector<uint32_t>& segment_frames = {}) {
  Model m;
  const uint32_t V = 6;
  m.meta.vertex_count = V;
  m.meta.frame_count = F;
  m.meta.frame_rate = 24.0;
  m.meta.tolerance = 1e-3;
  m.meta.diag = 3.5;
  m.meta.units = "m";
  m.faces = {0, 1, 2, 2, 1, 3, 3, 1, 4, 4, 5, 3};
  m.curves.vertices = {4, 0, 2, 5, 1, 3};
  m.curves.offsets = {0, 3, 6};
  m.curves.closed = {0, 1};
  m.curves.u = {0.f, 0.5f, 1.f, 0.f, 0.25f, 0.75f};
  for (size_t k = 1; k < segment_frames.size(); ++k) {
    Segment s;
    s.first_frame = segment_frames[k - 1];
    s.last_frame = segment_frames[k];
    s.motion.resize(m.curves.curve_count() * 3);
    m.segments.push_back(s);
  }
  m.residual.step = 0.25;
  m.residual.origin[0] = 0.5;
  m.residual.origin[1] = -1.0;
  m.residual.origin[2] = 2.0;
  m.residual.payload = encode_residuals(m, grid(V, F));
  return m;
}

// Exact position of the small model at frame f (origin + step * q), in double.
inline double grid_position(const Model& m, uint32_t f, uint32_t v, int a) {
  return m.residual.origin[a] + m.residual.step * grid_value(f, v, a);
}

}  // namespace dcurve::testing
