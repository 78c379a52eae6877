#include "codec/common/predictors.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "codec/common/crc32.h"

namespace dcurve {
namespace {

// Vertex adjacency (each undirected edge once per endpoint), sorted by neighbour id so
// the traversal is deterministic. Bucketed by vertex first: each list is short to sort.
void adjacency(const std::vector<uint32_t>& faces, uint32_t V, std::vector<uint32_t>* offsets,
               std::vector<uint32_t>* adj) {
  std::vector<uint32_t> start(size_t(V) + 1, 0), list(faces.size() / 3 * 6);
  auto for_each_edge = [&faces](auto&& visit) {
    for (size_t t = 0; t + 2 < faces.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = faces[t + size_t(k)], b = faces[t + size_t((k + 1) % 3)];
        if (a != b) visit(a, b);
      }
  };
  for_each_edge([&](uint32_t a, uint32_t b) { ++start[a + 1], ++start[b + 1]; });
  for (uint32_t v = 0; v < V; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  for_each_edge([&](uint32_t a, uint32_t b) { list[fill[a]++] = b, list[fill[b]++] = a; });
  offsets->assign(size_t(V) + 1, 0);
  adj->clear();
  adj->reserve(start[V]);
  for (uint32_t v = 0; v < V; ++v) {
    const auto begin = list.begin() + start[v], end = list.begin() + start[v + 1];
    std::sort(begin, end);
    adj->insert(adj->end(), begin, std::unique(begin, end));
    (*offsets)[v + 1] = uint32_t(adj->size());
  }
}

// The corners of `faces` as (edge the corner faces, its vertex), sorted by edge (min, max),
// then vertex: counted into buckets by the edge's smaller id first, so only each short
// bucket is sorted.
struct Corner {
  uint64_t edge;  // (min, max) vertex ids of the edge the corner faces
  uint32_t vertex;
};
std::vector<Corner> sorted_corners(const std::vector<uint32_t>& faces, uint32_t V) {
  auto key = [](uint64_t a, uint64_t b) { return a < b ? a << 32 | b : b << 32 | a; };
  std::vector<uint32_t> start(size_t(V) + 2, 0);
  for (size_t f = 0; f + 2 < faces.size(); f += 3)
    for (int k = 0; k < 3; ++k) ++start[std::min(faces[f + size_t((k + 1) % 3)], faces[f + size_t((k + 2) % 3)]) + 1];
  for (uint32_t v = 0; v <= V; ++v) start[v + 1] += start[v];
  std::vector<Corner> corners(start[V]);
  for (size_t f = 0; f + 2 < faces.size(); f += 3)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = faces[f + size_t(k)], a = faces[f + size_t((k + 1) % 3)], b = faces[f + size_t((k + 2) % 3)];
      corners[start[std::min(a, b)]++] = {key(a, b), v};
    }
  auto less = [](const Corner& x, const Corner& y) { return x.edge != y.edge ? x.edge < y.edge : x.vertex < y.vertex; };
  for (size_t i = 0, j = 0; i < corners.size(); i = j) {
    while (j < corners.size() && corners[j].edge >> 32 == corners[i].edge >> 32) ++j;
    std::sort(corners.begin() + std::ptrdiff_t(i), corners.begin() + std::ptrdiff_t(j), less);
  }
  return corners;
}

// Calls visit(v, a, b, c) for every face (v, a, b) whose a and b precede v and every face
// (a, b, c) across that edge whose c precedes v: the parallelogram (a, b, c) of v, in the
// order of the sorted corners.
template <class Visit>
void for_each_parallelogram(const std::vector<Corner>& corners, const std::vector<uint32_t>& pos, Visit&& visit) {
  for (size_t i = 0; i < corners.size();) {
    size_t j = i;
    while (j < corners.size() && corners[j].edge == corners[i].edge) ++j;
    const uint32_t a = uint32_t(corners[i].edge >> 32), b = uint32_t(corners[i].edge);
    for (size_t x = i; x < j; ++x) {
      const uint32_t v = corners[x].vertex;
      if (v == a || v == b || pos[a] >= pos[v] || pos[b] >= pos[v]) continue;
      for (size_t y = i; y < j; ++y) {
        const uint32_t c = corners[y].vertex;
        if (c == v || c == a || c == b || pos[c] >= pos[v]) continue;
        visit(v, a, b, c);
      }
    }
    i = j;
  }
}

// Every position's parallelograms (for_each_parallelogram), in traversal order: counted per
// vertex, then placed, so no list is grown per vertex.
void add_parallelograms(const std::vector<uint32_t>& faces, const std::vector<uint32_t>& pos, Traversal* t) {
  const uint32_t V = uint32_t(pos.size());
  const std::vector<Corner> corners = sorted_corners(faces, V);
  std::vector<uint32_t> count(size_t(V) + 1, 0);
  for_each_parallelogram(corners, pos, [&](uint32_t v, uint32_t, uint32_t, uint32_t) { ++count[v]; });
  t->para_offsets.assign(size_t(V) + 1, 0);
  std::vector<uint32_t> at(V);  // where vertex v's next parallelogram goes
  for (uint32_t i = 0; i < V; ++i) {
    at[t->order[i]] = t->para_offsets[i];
    t->para_offsets[i + 1] = t->para_offsets[i] + count[t->order[i]];
  }
  t->para.resize(size_t(t->para_offsets[V]) * 3);
  for_each_parallelogram(corners, pos, [&](uint32_t v, uint32_t a, uint32_t b, uint32_t c) {
    uint32_t* p = &t->para[size_t(at[v]++) * 3];
    p[0] = a, p[1] = b, p[2] = c;
  });
}

// Position i's earlier neighbours (adjacent vertices at positions < i, by id) and Fit set
// (those, then the vertices before i adjacent to one of them, by id; at most kMaxFitPoints),
// for t->order and pos its inverse.
void add_neighbour_sets(const std::vector<uint32_t>& off, const std::vector<uint32_t>& adj,
                        const std::vector<uint32_t>& pos, Traversal* out) {
  Traversal& t = *out;
  const uint32_t V = uint32_t(t.order.size());
  t.nb_offsets.assign(size_t(V) + 1, 0);
  t.nb.reserve(adj.size() / 2);  // each edge once, at its later end
  for (uint32_t i = 0; i < V; ++i) {
    const uint32_t v = t.order[i];
    for (uint32_t k = off[v]; k < off[v + 1]; ++k)
      if (pos[adj[k]] < i) t.nb.push_back(adj[k]);
    t.nb_offsets[i + 1] = uint32_t(t.nb.size());
  }
  std::vector<uint32_t> ring(adj.size()), seen(V, UINT32_MAX);  // seen[w] = i: w is in position i's set

  t.fit_offsets.assign(size_t(V) + 1, 0);
  t.fit.reserve(size_t(V) * kMaxFitPoints);
  for (uint32_t i = 0; i < V; ++i) {
    const uint32_t v = t.order[i], nb_begin = t.nb_offsets[i], nb_end = t.nb_offsets[i + 1];
    seen[v] = i;
    for (uint32_t k = nb_begin; k < nb_end; ++k) seen[t.nb[k]] = i;
    // Branch-free: every second neighbour is written, kept when earlier and new. Marking a
    // later one seen is harmless (it is never kept for i). The ring never outgrows adj.
    size_t n = 0;
    for (uint32_t k = nb_begin; k < nb_end; ++k)
      for (uint32_t j = off[t.nb[k]]; j < off[t.nb[k] + 1]; ++j) {
        const uint32_t w = adj[j];
        const bool keep = (pos[w] < i) & (seen[w] != i);
        seen[w] = i;
        ring[n] = w;
        n += keep;
      }
    std::sort(ring.begin(), ring.begin() + std::ptrdiff_t(n));
    t.fit.insert(t.fit.end(), t.nb.begin() + nb_begin, t.nb.begin() + nb_end);
    t.fit.insert(t.fit.end(), ring.begin(), ring.begin() + std::ptrdiff_t(n));
    t.fit.resize(std::min<size_t>(t.fit.size(), t.fit_offsets[i] + kMaxFitPoints));
    t.fit_offsets[i + 1] = uint32_t(t.fit.size());
  }
}

Traversal traversal_from_faces(const Model& m) {
  const uint32_t V = m.meta.vertex_count;
  std::vector<uint32_t> off, adj;
  adjacency(m.faces, V, &off, &adj);
  Traversal t;
  t.from_faces = true;
  t.order.reserve(V);
  std::vector<uint32_t> pos(V, UINT32_MAX);
  std::deque<uint32_t> queue;
  for (uint32_t seed = 0; seed < V; ++seed) {
    if (pos[seed] != UINT32_MAX) continue;
    pos[seed] = uint32_t(t.order.size());
    t.order.push_back(seed);
    queue.push_back(seed);
    while (!queue.empty()) {
      const uint32_t v = queue.front();
      queue.pop_front();
      for (uint32_t k = off[v]; k < off[v + 1]; ++k)
        if (pos[adj[k]] == UINT32_MAX) {
          pos[adj[k]] = uint32_t(t.order.size());
          t.order.push_back(adj[k]);
          queue.push_back(adj[k]);
        }
    }
  }
  add_neighbour_sets(off, adj, pos, &t);
  add_parallelograms(m.faces, pos, &t);
  return t;
}

Traversal traversal_from_curves(const Model& m) {
  Traversal t;
  const Curves& c = m.curves;
  t.order = c.vertices;
  t.nb_offsets.assign(t.order.size() + 1, 0);
  t.para_offsets.assign(t.order.size() + 1, 0);
  t.fit_offsets.assign(t.order.size() + 1, 0);
  for (uint32_t k = 0; k < c.curve_count(); ++k)
    for (uint32_t i = c.offsets[k]; i < c.offsets[k + 1]; ++i) {
      if (i > c.offsets[k]) t.nb.push_back(c.vertices[i - 1]);
      if (i > c.offsets[k] + 1) t.para.insert(t.para.end(), {c.vertices[i - 1], c.vertices[i - 1], c.vertices[i - 2]});
      // A curve vertex's neighbours are the previous and next ones: the Fit set is (p1, p2).
      for (uint32_t back = 1; back <= 2 && i >= c.offsets[k] + back; ++back) t.fit.push_back(c.vertices[i - back]);
      t.nb_offsets[i + 1] = uint32_t(t.nb.size());
      t.para_offsets[i + 1] = uint32_t(t.para.size() / 3);
      t.fit_offsets[i + 1] = uint32_t(t.fit.size());
    }
  return t;
}

}  // namespace

Traversal neighbour_traversal(const std::vector<uint32_t>& faces, std::vector<uint32_t> order) {
  const uint32_t V = uint32_t(order.size());
  std::vector<uint32_t> off, adj, pos(V);
  adjacency(faces, V, &off, &adj);
  Traversal t;
  t.from_faces = true;
  t.order = std::move(order);
  for (uint32_t i = 0; i < V; ++i) pos[t.order[i]] = i;
  add_neighbour_sets(off, adj, pos, &t);
  t.para_offsets.assign(size_t(V) + 1, 0);
  return t;
}

Traversal build_traversal(const Model& model) {
  return model.faces.empty() ? traversal_from_curves(model) : traversal_from_faces(model);
}

const Traversal& traversal_for(const Model& model, const ResidualOptions& options, Traversal* owned) {
  if (options.traversal) return *options.traversal;
  *owned = build_traversal(model);
  // Only walks that share tables need the mesh told apart; a decoder's never do.
  if (options.weights_source) {
    uint32_t crc = 0;
    for (const std::vector<uint32_t>* a :
         {&owned->order, &owned->nb_offsets, &owned->nb, &owned->para_offsets, &owned->para, &owned->fit_offsets, &owned->fit})
      crc = crc32c(a->data(), a->size() * sizeof(uint32_t), crc);
    owned->fingerprint = crc | 1;  // never 0
  }
  return *owned;
}

namespace {
// x / 2^s rounded down (also for negative x).
int64_t floor_shift(int64_t x, int s) { return x >= 0 ? x >> s : -((-x + (int64_t(1) << s) - 1) >> s); }

int32_t clamp_weight(int64_t w) { return int32_t(std::clamp<int64_t>(w, -kGeometricLimit, kGeometricLimit)); }

// Least-squares (alpha, beta) with v - a = alpha (b - a) + beta (c - a) in the geometry
// frame. The differences are scaled to 12 bits first, so every product fits in int64.
void triple_weights(const int32_t* qg, uint32_t v, uint32_t a, uint32_t b, uint32_t c, int32_t* w) {
  int64_t d1[3], d2[3], x[3], m = 0;
  for (int k = 0; k < 3; ++k) {
    const int64_t ga = qg[size_t(a) * 3 + size_t(k)];
    d1[k] = qg[size_t(b) * 3 + size_t(k)] - ga;
    d2[k] = qg[size_t(c) * 3 + size_t(k)] - ga;
    x[k] = qg[size_t(v) * 3 + size_t(k)] - ga;
    m = std::max({m, d1[k] < 0 ? -d1[k] : d1[k], d2[k] < 0 ? -d2[k] : d2[k], x[k] < 0 ? -x[k] : x[k]});
  }
  int s = 0;
  while ((m >> s) > 4095) ++s;
  int64_t g11 = 0, g12 = 0, g22 = 0, r1 = 0, r2 = 0;
  for (int k = 0; k < 3; ++k) {
    const int64_t p = floor_shift(d1[k], s), q = floor_shift(d2[k], s), y = floor_shift(x[k], s);
    g11 += p * p;
    g12 += p * q;
    g22 += q * q;
    r1 += p * y;
    r2 += q * y;
  }
  const int64_t det = g11 * g22 - g12 * g12;
  if (det <= 0) {  // a degenerate triangle (or a curve's (p1, p1, p2)): the plain parallelogram
    w[0] = kGeometricUnit;
    w[1] = -kGeometricUnit;
    return;
  }
  w[0] = clamp_weight(detail::rounded_mean(kGeometricUnit * (g22 * r1 - g12 * r2), det));
  w[1] = clamp_weight(detail::rounded_mean(kGeometricUnit * (g11 * r2 - g12 * r1), det));
}

// floor(a / b) for b > 0 and |a| < 2^62, given inverse = 1 / b: a binary64 quotient as the
// first guess, then made exact in int64. The same result as integer division on every
// platform (the guess only seeds it), and several times faster than a 64-bit divide, which
// dominates the weights; one inverse serves every weight of a set.
int64_t floor_div(int64_t a, int64_t b, double inverse) {
  int64_t q = int64_t(double(a) * inverse);  // truncated, not floored: no libm call
  int64_t r = a - q * b;
  while (r < 0) --q, r += b;
  while (r >= b) ++q, r -= b;
  return q;
}

int bit_length(int64_t x) {
  int b = 0;
  while (b < 63 && (x >> b) != 0) ++b;
  return b;
}

// Fit weights of one position: the affine function c + g . (x - x_v) fitted by least squares
// (ridge 16 on g, so flat and collinear sets stay solvable) to the set's values is, at v, the
// constant c = sum_j w_j value_j with w_j = (det - t . d_j) / (n det - t . s), where d_j are
// the offsets to v scaled to 7 bits, s their sum, C = sum d_j d_j^T + 16 I, det = det C and
// t = adj(C) s. With |d| <= 128 and n <= 16 every product below stays under 2^63.
void position_fit_weights(const int32_t* qg, uint32_t v, const uint32_t* set, uint32_t n, int32_t* w) {
  std::fill(w, w + n, 0);
  if (n < 2) return;
  int64_t d[kMaxFitPoints][3], m = 0;
  for (uint32_t j = 0; j < n; ++j)
    for (int k = 0; k < 3; ++k) {
      d[j][k] = int64_t(qg[size_t(set[j]) * 3 + size_t(k)]) - qg[size_t(v) * 3 + size_t(k)];
      m = std::max(m, d[j][k] < 0 ? -d[j][k] : d[j][k]);
    }
  int shift = 0;
  while ((m >> shift) > 127) ++shift;
  int64_t sum[3] = {0, 0, 0}, c[3][3] = {{16, 0, 0}, {0, 16, 0}, {0, 0, 16}};
  for (uint32_t j = 0; j < n; ++j) {
    for (int k = 0; k < 3; ++k) d[j][k] = floor_shift(d[j][k], shift);
    for (int k = 0; k < 3; ++k) {
      sum[k] += d[j][k];
      for (int l = 0; l < 3; ++l) c[k][l] += d[j][k] * d[j][l];
    }
  }
  const int64_t adj[3][3] = {
      {c[1][1] * c[2][2] - c[1][2] * c[2][1], c[0][2] * c[2][1] - c[0][1] * c[2][2], c[0][1] * c[1][2] - c[0][2] * c[1][1]},
      {c[1][2] * c[2][0] - c[1][0] * c[2][2], c[0][0] * c[2][2] - c[0][2] * c[2][0], c[0][2] * c[1][0] - c[0][0] * c[1][2]},
      {c[1][0] * c[2][1] - c[1][1] * c[2][0], c[0][1] * c[2][0] - c[0][0] * c[2][1], c[0][0] * c[1][1] - c[0][1] * c[1][0]}};
  const int64_t det = c[0][0] * adj[0][0] + c[0][1] * adj[1][0] + c[0][2] * adj[2][0];
  int64_t tv[3], ts = 0;
  for (int k = 0; k < 3; ++k) {
    tv[k] = adj[k][0] * sum[0] + adj[k][1] * sum[1] + adj[k][2] * sum[2];
    ts += tv[k] * sum[k];
  }
  const int64_t den = int64_t(n) * det - ts;
  if (den <= 0) return;  // cannot happen (C exceeds sum d d^T), but no division by it then
  const int scale = std::max(0, bit_length(den) - 30);
  const int64_t den_scaled = floor_shift(den, scale);
  const double inverse = 1.0 / double(2 * den_scaled);
  for (uint32_t j = 1; j < n; ++j) {
    const int64_t num = det - (tv[0] * d[j][0] + tv[1] * d[j][1] + tv[2] * d[j][2]);
    const int64_t num_scaled = std::clamp<int64_t>(floor_shift(num, scale), -(int64_t(1) << 40), int64_t(1) << 40);
    // rounded_mean(num_scaled * kFitUnit, den_scaled): floor((2 x + d) / (2 d)).
    const int64_t w_j = floor_div(2 * num_scaled * kFitUnit + den_scaled, 2 * den_scaled, inverse);
    w[j] = int32_t(std::clamp(w_j, -kFitLimit, kFitLimit));
  }
}
}  // namespace

std::vector<int32_t> fit_weights(const Traversal& t, const int32_t* qg) {
  std::vector<int32_t> w(t.fit.size());
  for (uint32_t pos = 0; pos + 1 < uint32_t(t.fit_offsets.size()); ++pos)
    position_fit_weights(qg, t.order[pos], t.fit.data() + t.fit_offsets[pos],
                         t.fit_offsets[pos + 1] - t.fit_offsets[pos], w.data() + t.fit_offsets[pos]);  // sets may all be empty
  return w;
}

std::vector<int32_t> spatial_weights(const Traversal& t, const int32_t* qg, SpatialMode mode) {
  if (mode == SpatialMode::Geometric) return geometric_weights(t, qg);
  if (mode == SpatialMode::Fit) return fit_weights(t, qg);
  return {};
}

std::vector<int32_t> geometric_weights(const Traversal& t, const int32_t* qg) {
  std::vector<int32_t> w(t.para.size() / 3 * 2);
  for (uint32_t pos = 0; pos + 1 < uint32_t(t.para_offsets.size()); ++pos)
    for (uint32_t k = t.para_offsets[pos]; k < t.para_offsets[pos + 1]; ++k)
      triple_weights(qg, t.order[pos], t.para[3 * size_t(k)], t.para[3 * size_t(k) + 1], t.para[3 * size_t(k) + 2],
                     &w[2 * size_t(k)]);
  return w;
}

const int32_t* SpatialWeightsCache::get(const Traversal& t, const int32_t* q, uint32_t g, SpatialMode mode) {
  // Least recently used goes first, so the (up to three) frames one cluster asked for last
  // stay valid while it asks for another.
  size_t i = 0;
  while (i < entries_.size() && entries_[i].g != g) ++i;
  if (i < entries_.size()) {
    std::rotate(entries_.begin() + std::ptrdiff_t(i), entries_.begin() + std::ptrdiff_t(i) + 1, entries_.end());
  } else {
    if (entries_.size() >= kCapacity) entries_.erase(entries_.begin());
    entries_.push_back({g, {}});
  }
  Entry& e = entries_.back();
  const bool fit = mode == SpatialMode::Fit;
  if (!e.tables[fit]) {
    const int32_t* qg = q + size_t(g) * t.order.size() * 3;
    e.tables[fit] = source_ ? source_->weights(t, qg, mode)
                            : std::make_shared<const std::vector<int32_t>>(spatial_weights(t, qg, mode));
  }
  return e.tables[fit]->data();
}

void SpatialWeightsCache::for_choice(const Traversal& t, const int32_t* q, const PredictorChoice* choice,
                                       const int32_t* out[3]) {
  for (int a = 0; a < 3; ++a)
    out[a] = uses_geometry(choice[a].spatial) ? get(t, q, choice[a].g, choice[a].spatial) : nullptr;
}

bool predictor_usable(const PredictorChoice& c, uint32_t f, const std::vector<uint8_t>& decoded,
                      const ResidualOptions& options) {
  auto ok = [&](uint32_t r) { return r < decoded.size() && r != f && decoded[r]; };
  if (uses_geometry(c.spatial) && !ok(c.g)) return false;
  auto near = [](uint32_t a, uint32_t b) { return (a > b ? a - b : b - a) <= kMaxLinearSpan; };
  switch (c.kind) {
    case PredictorKind::None: return true;
    case PredictorKind::Reference: return ok(c.r0);
    case PredictorKind::Linear:
      return ok(c.r0) && ok(c.r1) && c.r0 != c.r1 && near(c.r0, f) && near(c.r1, c.r0);
    case PredictorKind::Model: return options.model_prediction != nullptr || options.model_frames != nullptr;
    case PredictorKind::Motion: return ok(c.r0);
  }
  return false;
}

void base_prediction(const PredictorChoice& c, uint32_t f, int axis, uint32_t V, const int32_t* q,
                     const ResidualOptions& options, int64_t* base) {
  const size_t stride = size_t(V) * 3, a = size_t(axis);
  switch (c.kind) {
    case PredictorKind::None:
      std::fill(base, base + V, int64_t(0));
      return;
    case PredictorKind::Reference:
    case PredictorKind::Motion: {
      const int32_t* r = q + size_t(c.r0) * stride;
      for (uint32_t v = 0; v < V; ++v) base[v] = r[size_t(v) * 3 + a];
      return;
    }
    case PredictorKind::Linear: {
      const int32_t* p0 = q + size_t(c.r0) * stride;
      const int32_t* p1 = q + size_t(c.r1) * stride;
      int64_t t = int64_t(f) - int64_t(c.r0), span = int64_t(c.r1) - int64_t(c.r0);
      if (span < 0) { span = -span; t = -t; }
      for (uint32_t v = 0; v < V; ++v) {
        const int64_t y0 = p0[size_t(v) * 3 + a], y1 = p1[size_t(v) * 3 + a];
        base[v] = y0 + detail::rounded_mean((y1 - y0) * t, span);
      }
      return;
    }
    case PredictorKind::Model: {
      const int32_t* mp = options.model_prediction->data() + size_t(f) * stride;
      for (uint32_t v = 0; v < V; ++v) base[v] = mp[size_t(v) * 3 + a];
      return;
    }
  }
}

}  // namespace dcurve
