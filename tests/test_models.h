// Small deterministic models shared by the container, decoder and test-vector tests. Every
// value comes from a closed formula, so expected positions are computed here, independently
// of the decoder.
#pragma once
#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "codec/common/basis.h"
#include "codec/common/model.h"
#include "codec/common/residual.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/quantize.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/residual_decoder.h"

namespace dcurve::testing {

// Grid value of frame f, vertex v, axis a: smooth in f with a vertex- and axis-dependent
// offset, negative values included. The (v * v * (a + 2)) % 11 term keeps the vertices off
// one line, so Geometric weights (format_spec/residual.md) are not all degenerate.
inline int32_t grid_value(uint32_t f, uint32_t v, int a) {
  return int32_t(v * 7 + a * 3) - 9 + int32_t(f * f) * (a + 1) - int32_t(f * v % 5) + int32_t(v * v * uint32_t(a + 2) % 11);
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
  // As a reader returns them (16-bit fixed point), so double references see the same u.
  for (float u : {0.f, 0.5f, 1.f, 0.f, 0.25f, 0.75f}) m.curves.u.push_back(quantize_curve_u(u));
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

// `m` without faces, its residual layer recoded to match: the residual predicts from mesh
// neighbours when faces are stored and from curve neighbours otherwise, so a file written
// without connectivity must have been coded without it.
inline Model without_faces(Model m) {
  m.faces.clear();
  m.residual.payload = encode_residuals(m, grid(m.meta.vertex_count, m.meta.frame_count));
  return m;
}

// An n x n vertex sheet (2 (n-1)^2 triangles, consistently wound) whose vertex ids are
// scrambled by a fixed permutation, one open curve per row, F frames of grid() positions,
// no segments. Scrambled ids make the FACE Traversal layout pay off.
inline Model sheet_model(uint32_t n, uint32_t F) {
  Model m = small_model(F);
  const uint32_t V = n * n;
  auto id = [&](uint32_t row, uint32_t col) { return (row * n + col) * 7919u % V; };  // 7919 prime, V < 7919
  m.meta.vertex_count = V;
  m.faces.clear();
  for (uint32_t r = 0; r + 1 < n; ++r)
    for (uint32_t c = 0; c + 1 < n; ++c)
      m.faces.insert(m.faces.end(), {id(r, c), id(r, c + 1), id(r + 1, c), id(r + 1, c), id(r, c + 1), id(r + 1, c + 1)});
  m.curves = Curves{};
  for (uint32_t r = 0; r < n; ++r) {
    m.curves.offsets.push_back(r * n);
    m.curves.closed.push_back(0);
    for (uint32_t c = 0; c < n; ++c) {
      m.curves.vertices.push_back(id(r, c));
      m.curves.u.push_back(quantize_curve_u(float(c) / float(n - 1)));
    }
  }
  m.curves.offsets.push_back(V);
  m.residual.payload = encode_residuals(m, grid(V, F));
  return m;
}

// Exact position of the small model at frame f (origin + step * q), in double.
inline double grid_position(const Model& m, uint32_t f, uint32_t v, int a) {
  return m.residual.origin[a] + m.residual.step * grid_value(f, v, a);
}

// Gives every segment motion a PDE model with deterministic parameters and coefficients:
// cycles through Pde8 cases 0..3, Pde32 and Zero, parameters on both sides of the basis
// switch value (8), coefficients of about a grid step or two.
inline void add_pde_motions(Model* m, uint32_t seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> coeff(-0.5f, 0.5f);
  const float params[] = {0.f, 0.3f, 2.5f, 9.f, 20.f};
  int k = 0;
  for (Segment& s : m->segments)
    for (CurveMotion& cm : s.motion) {
      const int kind = k++ % 6;
      cm = CurveMotion{};
      if (kind == 5) continue;  // Zero
      cm.basis = kind < 4 ? Basis::Pde8 : Basis::Pde32;
      cm.basis_case = uint8_t(kind < 4 ? kind : 0);
      cm.time_param = params[rng() % 5];
      cm.space_param = params[rng() % 5];
      cm.coeffs.resize(size_t(basis_term_count(cm.basis)));
      for (float& c : cm.coeffs) c = coeff(rng);
      quantize_coefficients(&cm, -int(rng() % 30));  // what a file can store, coarse or fine
    }
}

// Curve c of vertex v and its position j in curves.vertices.
inline void locate(const Model& m, uint32_t v, uint32_t* c, uint32_t* j) {
  for (*c = 0; *c < m.curves.curve_count(); ++*c)
    for (*j = m.curves.offsets[*c]; *j < m.curves.offsets[*c + 1]; ++*j)
      if (m.curves.vertices[*j] == v) return;
}

// M_s at frame coordinate x for segment `seg` (model units, rest pose included).
inline double segment_model(const Model& m, const Segment& seg, double x, uint32_t v, int a) {
  const uint32_t len = seg.last_frame - seg.first_frame;
  const double tau = len ? (x - seg.first_frame) / len : 0.0;
  uint32_t c = 0, j = 0;
  locate(m, v, &c, &j);
  double value = evaluate_motion(seg.motion[c * 3 + a], tau, m.curves.u[j]);
  if (seg.mode == FitMode::Displacement) value += grid_position(m, 0, v, a);
  return value;
}

// The segment frame coordinate x falls in (later wins on a shared frame).
inline const Segment& segment_at(const Model& m, double x) {
  const Segment* seg = &m.segments[0];
  for (const Segment& s : m.segments)
    if (double(s.first_frame) <= x) seg = &s;
  return *seg;
}

// The reference output for any file the helpers make: linear interpolation of the grid when
// there are no segments, the model alone when there is no residual layer, else
// reference_position below.
inline double reference_position(const Model& m, double x, uint32_t v, int a);
inline double expected_position(const Model& m, double x, uint32_t v, int a) {
  if (m.segments.empty()) {
    const uint32_t F = m.meta.frame_count;
    const uint32_t i = F > 1 ? std::min(uint32_t(x), F - 2) : 0;
    const double w = F > 1 ? x - i : 0.0;
    return (1 - w) * grid_position(m, i, v, a) + (w != 0 ? w * grid_position(m, i + 1, v, a) : 0.0);
  }
  if (m.residual.step == 0) return segment_model(m, segment_at(m, x), x, v, a);
  return reference_position(m, x, v, a);
}

// The whole reference output at frame coordinate x, written from the spec's formulas:
// M_s(x) + lerp(X_i - M_s(i), X_{i+1} - M_s(i+1), w), s the segment x falls in (later wins).
inline double reference_position(const Model& m, double x, uint32_t v, int a) {
  const Segment& seg = segment_at(m, x);
  const uint32_t len = seg.last_frame - seg.first_frame;
  uint32_t i = seg.first_frame;
  double w = 0;
  if (len) {
    i = std::min(uint32_t(x), seg.last_frame - 1);
    w = x - i;
  }
  auto correction = [&](uint32_t f) { return grid_position(m, f, v, a) - segment_model(m, seg, f, v, a); };
  return segment_model(m, seg, x, v, a) + (1 - w) * correction(i) + (w != 0 ? w * correction(i + 1) : 0.0);
}

}  // namespace dcurve::testing
