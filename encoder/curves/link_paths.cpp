#include "encoder/curves/link_paths.h"

#include "encoder/curves/join_runs.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dcurve {
namespace curves_detail {
namespace {

struct Vec {
  double x, y, z;
};
Vec sub(const std::vector<float>& xyz, uint32_t to, uint32_t from) {
  return {double(xyz[3 * to]) - xyz[3 * from], double(xyz[3 * to + 1]) - xyz[3 * from + 1],
          double(xyz[3 * to + 2]) - xyz[3 * from + 2]};
}
double dot(const Vec& a, const Vec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

class DisjointSets {
 public:
  explicit DisjointSets(uint32_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0u); }
  uint32_t find(uint32_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  uint32_t size(uint32_t v) { return size_[find(v)]; }
  void unite(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<uint32_t> parent_, size_;
};

class Linker {
 public:
  Linker(const std::vector<float>& xyz, uint32_t vertex_count)
      : xyz_(xyz), sets_(vertex_count), nbr_(size_t(vertex_count) * 2, kNoVertex) {}

  uint32_t degree(uint32_t v) const { return (nbr_[2 * v] != kNoVertex) + (nbr_[2 * v + 1] != kNoVertex); }

  // Links a-b if both have a free slot, the turns at a and b have cosine >= min_cos, and the
  // link closes no cycle (none at all unless may_close, never one below 3 vertices).
  // `max_short` > 0 demands that one of the two runs has fewer than max_short vertices.
  bool try_link(uint32_t a, uint32_t b, double min_cos, uint32_t max_short, bool may_close) {
    if (degree(a) == 2 || degree(b) == 2) return false;
    const bool same_run = sets_.find(a) == sets_.find(b);
    if (same_run && (!may_close || sets_.size(a) < 3)) return false;
    if (max_short > 0 && std::min(sets_.size(a), sets_.size(b)) >= max_short) return false;
    // The existing neighbour of an end vertex is always in slot 0.
    if (degree(a) == 1 && turn_cosine(xyz_, nbr_[2 * a], a, b) < min_cos) return false;
    if (degree(b) == 1 && turn_cosine(xyz_, a, b, nbr_[2 * b]) < min_cos) return false;
    nbr_[2 * a + degree(a)] = b;
    nbr_[2 * b + degree(b)] = a;
    sets_.unite(a, b);
    return true;
  }

  std::vector<uint32_t> release() { return std::move(nbr_); }

 private:
  const std::vector<float>& xyz_;
  DisjointSets sets_;
  std::vector<uint32_t> nbr_;
};

double alignment(const std::vector<float>& xyz, const std::vector<float>& dir, uint32_t a, uint32_t b) {
  const Vec e = sub(xyz, b, a);
  const double len = std::sqrt(dot(e, e));
  if (!(len > 0.0)) return 0.0;
  const Vec ta{dir[3 * a], dir[3 * a + 1], dir[3 * a + 2]};
  const Vec tb{dir[3 * b], dir[3 * b + 1], dir[3 * b + 2]};
  return 0.5 * (std::fabs(dot(e, ta)) + std::fabs(dot(e, tb))) / len;
}

}  // namespace

double turn_cosine(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c) {
  const Vec d1 = sub(xyz, b, a), d2 = sub(xyz, c, b);
  const double n = std::sqrt(dot(d1, d1) * dot(d2, d2));
  return n > 0.0 ? dot(d1, d2) / n : 1.0;
}

double turn_angle(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c) {
  return std::acos(std::clamp(turn_cosine(xyz, a, b, c), -1.0, 1.0));
}

PathLinks link_along_field(const SurfaceGraph& g, const std::vector<float>& xyz,
                           const std::vector<float>& dir, const LinkParams& params) {
  // Edges in order of decreasing alignment, bucketed (a counting sort: alignment differences
  // below 1/4096 do not matter) and by edge index within a bucket, so the order is deterministic.
  constexpr uint32_t kBuckets = 4096;
  const size_t E = g.edges.size();
  std::vector<uint32_t> bucket(E), start(kBuckets + 1, 0);
  for (size_t e = 0; e < E; ++e) {
    const double a = alignment(xyz, dir, g.edges[e][0], g.edges[e][1]);
    bucket[e] = kBuckets - 1 - std::min(kBuckets - 1, uint32_t(a * kBuckets));
    ++start[bucket[e] + 1];
  }
  for (uint32_t k = 0; k < kBuckets; ++k) start[k + 1] += start[k];
  std::vector<uint32_t> order(E);
  for (size_t e = 0; e < E; ++e) order[start[bucket[e]]++] = uint32_t(e);

  const double deg = M_PI / 180.0;
  Linker linker(xyz, g.vertex_count);
  for (const LinkPass& pass : params.passes) {
    const double min_cos = pass.max_turn_deg >= 180.0 ? -2.0 : std::cos(pass.max_turn_deg * deg);
    for (uint32_t edge : order) {
      const auto& e = g.edges[edge];
      linker.try_link(e[0], e[1], min_cos, pass.short_points, pass.may_close);
    }
  }

  PathLinks links{linker.release()};
  if (params.join_sweeps > 0) join_runs_through_neighbours(g, xyz, params.max_join_bend, params.join_sweeps, &links);
  thread_lonely_vertices(g, xyz, &links);
  return links;
}

void assemble_paths(const PathLinks& links, Curves* out) {
  const uint32_t V = uint32_t(links.nbr.size() / 2);
  out->vertices.clear();
  out->offsets.assign(1, 0);
  out->closed.clear();
  out->u.clear();
  out->vertices.reserve(V);
  std::vector<uint8_t> seen(V, 0);
  auto walk = [&](uint32_t start, bool closed) {
    uint32_t prev = kNoVertex, v = start;
    while (v != kNoVertex && !seen[v]) {
      seen[v] = 1;
      out->vertices.push_back(v);
      const uint32_t next = links.nbr[2 * v] != prev ? links.nbr[2 * v] : links.nbr[2 * v + 1];
      prev = v;
      v = next;
    }
    out->offsets.push_back(uint32_t(out->vertices.size()));
    out->closed.push_back(closed ? 1 : 0);
  };
  // Open runs first visit from their smaller end: an end has at most one neighbour, in slot 0.
  for (uint32_t v = 0; v < V; ++v)
    if (!seen[v] && links.nbr[2 * v + 1] == kNoVertex) walk(v, false);
  for (uint32_t v = 0; v < V; ++v)
    if (!seen[v]) walk(v, true);
}

}  // namespace curves_detail
}  // namespace dcurve
