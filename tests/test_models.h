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

// The blend of corrections c(f), f in the segment [a, b], at frame coordinate i + w by an
// in-between rule (format_spec/dcrv.md section 13), written from the spec's formulas apart
// from the decoder's weights (codec/common/inbetween.cpp).
template <class Correction>
double reference_blend(Inbetween rule, uint32_t a, uint32_t b, uint32_t i, double w, Correction c) {
  if (w == 0) return c(i);
  if (rule == Inbetween::Linear) return (1 - w) * c(i) + w * c(i + 1);
  auto tangent = [&](uint32_t f) {
    if (b - a == 1) return c(b) - c(a);
    if (f == a) return (-3 * c(a) + 4 * c(a + 1) - c(a + 2)) / 2;
    if (f == b) return (3 * c(b) - 4 * c(b - 1) + c(b - 2)) / 2;
    if (rule == Inbetween::Hermite4 && f >= a + 2 && f + 2 <= b)
      return (c(f - 2) - 8 * c(f - 1) + 8 * c(f + 1) - c(f + 2)) / 12;
    return (c(f + 1) - c(f - 1)) / 2;
  };
  const double w2 = w * w, w3 = w2 * w;
  return (2 * w3 - 3 * w2 + 1) * c(i) + (w3 - 2 * w2 + w) * tangent(i) + (-2 * w3 + 3 * w2) * c(i + 1) +
         (w3 - w2) * tangent(i + 1);
}

// The reference output for any file the helpers make: the model alone when there is no
// residual layer, else reference_position below.
inline double reference_position(const Model& m, double x, uint32_t v, int a);
inline double expected_position(const Model& m, double x, uint32_t v, int a) {
  if (!m.segments.empty() && m.residual.step == 0) return segment_model(m, segment_at(m, x), x, v, a);
  return reference_position(m, x, v, a);
}

// The whole reference output at frame coordinate x, written from the spec's formulas:
// M_s(x) + blend of D(f) = X_f - M_s(f) around x by the file's rule, s the segment x falls
// in (later wins); without segments one segment [0, F - 1] and no model.
inline double reference_position(const Model& m, double x, uint32_t v, int a) {
  Segment whole;
  whole.last_frame = m.meta.frame_count - 1;
  const bool none = m.segments.empty();
  const Segment& seg = none ? whole : segment_at(m, x);
  const uint32_t len = seg.last_frame - seg.first_frame;
  uint32_t i = seg.first_frame;
  double w = 0;
  if (len) {
    i = std::min(uint32_t(x), seg.last_frame - 1);
    w = x - i;
  }
  auto model = [&](double at) { return none ? 0.0 : segment_model(m, seg, at, v, a); };
  auto correction = [&](uint32_t f) { return grid_position(m, f, v, a) - model(f); };
  return model(x) + reference_blend(m.meta.inbetween, seg.first_frame, seg.last_frame, i, w, correction);
}

}  // namespace dcurve::testing
