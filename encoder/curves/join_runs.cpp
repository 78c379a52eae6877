#include "encoder/curves/join_runs.h"

#include <cmath>

namespace dcurve {
namespace curves_detail {
namespace {

// The links as two slots per vertex; an end vertex keeps its one neighbour in slot 0.
class Runs {
 public:
  explicit Runs(std::vector<uint32_t>* nbr) : nbr_(*nbr), label_(nbr->size() / 2, kNoVertex) {
    for (uint32_t v = 0; v < label_.size(); ++v)
      if (label_[v] == kNoVertex) relabel(v);
  }

  uint32_t degree(uint32_t v) const { return (nbr_[2 * v] != kNoVertex) + (nbr_[2 * v + 1] != kNoVertex); }
  uint32_t slot(uint32_t v, int k) const { return nbr_[2 * v + k]; }
  uint32_t other(uint32_t v, uint32_t not_this) const { return nbr_[2 * v] != not_this ? nbr_[2 * v] : nbr_[2 * v + 1]; }
  uint32_t label(uint32_t v) const { return label_[v]; }

  void link(uint32_t a, uint32_t b) {
    nbr_[2 * a + degree(a)] = b;
    nbr_[2 * b + degree(b)] = a;
  }
  void unlink(uint32_t a, uint32_t b) {
    drop(a, b);
    drop(b, a);
  }

  // The far end reached from `start` when leaving it away from `from`.
  uint32_t far_end(uint32_t start, uint32_t from) const {
    uint32_t prev = from, v = start;
    for (;;) {
      const uint32_t next = other(v, prev);
      if (next == kNoVertex || next == start) return v;
      prev = v;
      v = next;
    }
  }

  // Gives every vertex of v's run (or cycle) the label v.
  void relabel(uint32_t v) {
    label_[v] = v;
    for (int k = 0; k < 2; ++k) {
      uint32_t prev = v, w = nbr_[2 * v + k];
      while (w != kNoVertex && w != v) {
        label_[w] = v;
        const uint32_t next = other(w, prev);
        prev = w;
        w = next;
      }
      if (w == v) break;  // a cycle: one direction covers it
    }
  }

 private:
  void drop(uint32_t a, uint32_t b) {
    if (nbr_[2 * a] == b) {
      nbr_[2 * a] = nbr_[2 * a + 1];
      nbr_[2 * a + 1] = kNoVertex;
    } else if (nbr_[2 * a + 1] == b) {
      nbr_[2 * a + 1] = kNoVertex;
    }
  }

  std::vector<uint32_t>& nbr_;
  std::vector<uint32_t> label_;
};

// 1 - cos of the turn a -> b -> c, or 0 when any of them is missing.
double bend(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c) {
  if (a == kNoVertex || b == kNoVertex || c == kNoVertex) return 0.0;
  return 1.0 - turn_cosine(xyz, a, b, c);
}

struct Move {
  uint32_t x, y, b;
  double added;
};

}  // namespace

void join_runs_through_neighbours(const SurfaceGraph& g, const std::vector<float>& xyz, double max_added_bend,
                                  uint32_t sweeps, PathLinks* links) {
  Runs runs(&links->nbr);
  for (uint32_t sweep = 0; sweep < sweeps; ++sweep) {
    uint32_t joined = 0;
    for (uint32_t a = 0; a < g.vertex_count; ++a) {
      if (runs.degree(a) == 2) continue;
      const uint32_t a_prev = runs.slot(a, 0);  // kNoVertex when a is alone
      Move best{kNoVertex, kNoVertex, kNoVertex, max_added_bend};
      for (uint32_t i = g.adj_offsets[a]; i < g.adj_offsets[a + 1]; ++i) {
        const uint32_t x = g.adj[i];
        if (runs.degree(x) != 2 || runs.label(x) == runs.label(a)) continue;
        for (int k = 0; k < 2; ++k) {
          const uint32_t y = runs.slot(x, k), z = runs.slot(x, 1 - k);
          const uint32_t y_next = runs.other(y, x);
          const double removed = bend(xyz, y, x, z) + bend(xyz, x, y, y_next);
          const double base = bend(xyz, a_prev, a, x) + bend(xyz, a, x, z) - removed;
          for (uint32_t j = g.adj_offsets[y]; j < g.adj_offsets[y + 1]; ++j) {
            const uint32_t b = g.adj[j];
            if (b == x) continue;
            const uint32_t b_degree = runs.degree(b) + (b == a ? 1 : 0);
            if (b_degree >= 2) continue;
            const uint32_t b_prev = b == a ? x : runs.slot(b, 0);
            const double added = base + bend(xyz, b, y, y_next) + bend(xyz, b_prev, b, y);
            if (!(added < best.added)) continue;
            // b must not lie on y's side of the cut run, or y-b would close a cycle.
            if (runs.label(b) == runs.label(x) && runs.far_end(y, x) == b) continue;
            best = Move{x, y, b, added};
          }
        }
      }
      if (best.x == kNoVertex) continue;
      runs.unlink(best.x, best.y);
      runs.link(a, best.x);
      runs.link(best.y, best.b);
      runs.relabel(a);
      runs.relabel(best.y);
      ++joined;
    }
    if (joined == 0) break;
  }
}

void thread_lonely_vertices(const SurfaceGraph& g, const std::vector<float>& xyz, PathLinks* links) {
  std::vector<uint32_t>& nbr = links->nbr;
  auto linked = [&](uint32_t a, uint32_t b) { return nbr[2 * a] == b || nbr[2 * a + 1] == b; };
  auto distance = [&](uint32_t a, uint32_t b) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) s += (double(xyz[3 * a + k]) - xyz[3 * b + k]) * (double(xyz[3 * a + k]) - xyz[3 * b + k]);
    return std::sqrt(s);
  };
  for (uint32_t s = 0; s < g.vertex_count; ++s) {
    if (nbr[2 * s] != kNoVertex) continue;
    double best = HUGE_VAL;
    uint32_t best_a = kNoVertex, best_b = kNoVertex;
    for (uint32_t i = g.adj_offsets[s]; i < g.adj_offsets[s + 1]; ++i)
      for (uint32_t j = i + 1; j < g.adj_offsets[s + 1]; ++j) {
        const uint32_t a = g.adj[i], b = g.adj[j];
        if (!linked(a, b)) continue;
        const double detour = distance(s, a) + distance(s, b) - distance(a, b);
        if (detour < best) {
          best = detour;
          best_a = a;
          best_b = b;
        }
      }
    if (best_a == kNoVertex) continue;
    for (int k = 0; k < 2; ++k) {
      if (nbr[2 * best_a + k] == best_b) nbr[2 * best_a + k] = s;
      if (nbr[2 * best_b + k] == best_a) nbr[2 * best_b + k] = s;
    }
    nbr[2 * s] = best_a;
    nbr[2 * s + 1] = best_b;
  }
}

}  // namespace curves_detail
}  // namespace dcurve
