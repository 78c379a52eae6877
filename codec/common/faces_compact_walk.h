// The traversal of FACE layout 2, Compact (codec/common/faces_compact.h), that its writer
// (codec/compress/faces_compact_encoder.cpp) and its reader
// (codec/decompress/faces_compact_decoder.cpp) both run, with the models both adapt.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <stdexcept>
#include <vector>

#include "codec/common/bit_model.h"
#include "codec/common/error.h"
#include "codec/common/faces_compact.h"
#include "codec/common/flat_index.h"
#include "codec/common/id_ranks.h"
#include "codec/common/int_coder.h"

namespace dcurve {
namespace faces_compact_walk {

// Recent border edges remembered per vertex and direction: on a manifold mesh the one that
// closes a triangle is among the last few at that vertex; a bound keeps a hostile fan cheap.
constexpr int kRing = 8;
constexpr int kMaxCandidates = 2 * kRing;
// New-vertex id predictors, from which the id's rank among the unused ids is coded: the
// larger and the smaller gate id, a + b - c (ids of a grid numbered row by row form
// parallelograms), the last new id (meshes numbered in a traversal of their own).
constexpr int kPredictors = 4;
constexpr int kGapClasses = 4;
constexpr int kFanClasses = 7;
constexpr int kSideGap = 2;
// Integer coder contexts: new-vertex deltas per (predictor, gap class), then three singles.
constexpr int kCtxFar = kPredictors * kGapClasses;
constexpr int kCtxStartNew = kCtxFar + 1;
constexpr int kCtxStartSeen = kCtxFar + 2;
constexpr int kIntContexts = kCtxFar + 3;
constexpr int kSignOther = kPredictors * 9;
constexpr int kSignContexts = kSignOther + 1;

inline int bit_length(uint64_t m) { return m ? floor_log2(m) + 1 : 0; }
inline uint64_t edge_key(uint32_t from, uint32_t to) { return uint64_t(from) << 32 | to; }

// How far apart the ids of the gate's two vertices are: a gate between nearby ids tends to
// get a new vertex with a nearby id too.
inline int gap_class(uint64_t free_between) {
  const int n = bit_length(free_between);
  return n <= 1 ? 0 : n <= 3 ? 1 : n <= 6 ? 2 : 3;
}

struct Models {
  BitModel follows[6];   // [edge index * 2 + twin already out]
  // Whether x is a candidate, [sides with candidates - 1][fan(a)][fan(b)]: a vertex whose fan
  // already holds about as many triangles as a typical valence is about to be closed.
  BitModel in_list[3][kFanClasses][kFanClasses];
  BitModel first_index[kFanClasses][kFanClasses];  // unary candidate index, position 0
  BitModel index[2];                               // positions 1 and >= 2
  BitModel is_new[2];    // [candidates > 0]
  BitModel start_new;
  BitModel far_side[kGapClasses][2];  // [gap][b > a]: base the rank on min(a, b), not max(a, b)
  AdaptiveIntCoder ints{kIntContexts, kSignContexts};
};

// What both sides know about the triangles out so far: the vertices seen, the directed
// edges out, and per vertex its most recent incoming and outgoing edges.
class Region {
 public:
  // Vertex ids below `bound` (the file's vertex count): per-vertex state is a flat array.
  explicit Region(uint32_t bound) : slot_(bound, kUnseen), ids_(bound) {}
  uint32_t bound() const { return ids_.bound(); }
  bool seen(uint32_t v) const { return v < slot_.size() && slot_[v] != kUnseen; }
  // v < bound(); no effect when already seen.
  void mark_seen(uint32_t v) {
    if (slot_[v] != kUnseen) return;
    slot_[v] = uint32_t(rings_.size());
    rings_.emplace_back();
    ids_.insert(v);
  }
  const IdRanks& ids() const { return ids_; }
  // Room for about `triangles` triangles of a closed mesh (half as many vertices).
  void reserve(size_t triangles) { rings_.reserve(std::min<size_t>(triangles / 2 + 3, slot_.size())); }
  // Triangles out around v so far, clamped to kFanClasses - 1.
  int fan(uint32_t v) const { return int(std::min<uint32_t>(ring(v).into.count, kFanClasses - 1)); }
  // Whether the directed edge from -> to is out. A vertex's from list holds all its edges
  // out until it has more than kRing (a manifold vertex rarely does): only those go to a table.
  bool has_edge(uint32_t from, uint32_t to) const {
    if (!seen(from)) return false;
    const Recent& out = ring(from).from;
    if (out.count > kRing) return edges_.contains(edge_key(from, to));
    return out.holds(to);
  }
  // All three corners must have been marked seen.
  void add_triangle(const uint32_t* t) {
    for (int c = 0; c < 3; ++c) {
      const uint32_t u = t[c], v = t[(c + 1) % 3];
      Recent& out = ring(u).from;
      if (out.count == kRing)  // u's list is about to drop its oldest edge: all it holds go to the table
        for (uint32_t w : out.ids) edges_.insert(edge_key(u, w), 0);
      if (out.count >= kRing) edges_.insert(edge_key(u, v), 0);
      ring(v).into.push(u);
      out.push(v);
    }
  }
  // The vertices x that would close a triangle (b, a, x) against the border of the region:
  // an open edge x -> a (its twin a -> x not out), then an open edge b -> x; most recent
  // first, without a, b or repeats. Returns how many were written (<= kMaxCandidates);
  // *from_a = how many of them came from the edges into a.
  int candidates(uint32_t a, uint32_t b, uint32_t* out, int* from_a) const {
    int n = 0;
    auto offer = [&](uint32_t w, bool open) {
      if (w == a || w == b || !open || listed(out, n, w)) return;
      out[n++] = w;
    };
    const Recent& into_a = ring(a).into;
    for (uint32_t k = 0; k < into_a.size(); ++k) offer(into_a.back(k), !has_edge(a, into_a.back(k)));
    *from_a = n;
    const Recent& from_b = ring(b).from;
    for (uint32_t k = 0; k < from_b.size(); ++k) offer(from_b.back(k), !has_edge(from_b.back(k), b));
    return n;
  }

 private:
  struct Recent {
    uint32_t ids[kRing] = {};
    uint32_t count = 0;
    void push(uint32_t v) { ids[count++ % kRing] = v; }
    uint32_t size() const { return std::min<uint32_t>(count, kRing); }
    uint32_t back(uint32_t k) const { return ids[(count - 1 - k) % kRing]; }  // k = 0: newest
    // Whether v is among the first size() entries: a fixed-length loop without early exit,
    // which compiles to a few vector compares (this is the walk's most frequent question).
    bool holds(uint32_t v) const {
      bool hit = false;
      for (uint32_t k = 0; k < kRing; ++k) hit |= (ids[k] == v) & (k < count);
      return hit;
    }
  };
  // Whether v is among list[0..n), n <= kMaxCandidates: as Recent::holds.
  static bool listed(const uint32_t* list, int n, uint32_t v) {
    bool hit = false;
    for (int k = 0; k < kMaxCandidates; ++k) hit |= (list[k] == v) & (k < n);
    return hit;
  }
  struct Rings {
    Recent into, from;
  };
  static constexpr uint32_t kUnseen = UINT32_MAX;
  // Only for seen vertices (as std::vector::at, a missing one is a logic error, not UB).
  uint32_t slot(uint32_t v) const {
    if (!seen(v)) throw std::out_of_range("faces_compact_walk: vertex not seen");
    return slot_[v];
  }
  Rings& ring(uint32_t v) { return rings_[slot(v)]; }
  const Rings& ring(uint32_t v) const { return rings_[slot(v)]; }
  std::vector<uint32_t> slot_;  // vertex id -> its Rings, or kUnseen
  std::vector<Rings> rings_;
  FlatIndex edges_;  // directed edges out of vertices with more than kRing of them (values unused)
  IdRanks ids_;
};

// The two directions of one traversal: the encoder's Io codes the decision it is given and
// returns it, the decoder's ignores it and returns what the stream says.
// codec/compress/faces_compact_encoder.cpp defines the encoder's (EncodeIo),
// codec/decompress/faces_compact_decoder.cpp the decoder's (DecodeIo).

// Checks a coded id against what its flag claims and marks it seen.
inline bool accept(Region& region, int64_t id, bool is_new, std::string* error) {
  if (id < 0 || id >= int64_t(region.bound())) return fail(error, "face vertex id out of range");
  if (is_new == region.seen(uint32_t(id)))
    return fail(error, is_new ? "face vertex coded as new was already used" : "face vertex coded as known was never used");
  region.mark_seen(uint32_t(id));
  return true;
}

// Codes new vertices' ids: each by its rank among the unused ids, seen from a prediction
// picked without side information (the one whose ranks were shortest, in an exponentially
// decaying sum of bit lengths), or from the nearer gate id when the gate's ids are far apart.
class NewIds {
 public:
  void starts_at(int64_t id) { last_new_ = id; }

  // The new third corner x of (b, a, x), crossing edge (a, b) of a triangle whose third
  // corner is c. Decoding, x is ignored and *out receives the id.
  template <class Io>
  bool code(Io& io, Models& m, Region& region, uint32_t a, uint32_t b, uint32_t c, uint32_t x, uint32_t* out,
            std::string* error) {
    const IdRanks& ids = region.ids();
    const int64_t p[kPredictors] = {std::max(a, b), std::min(a, b), int64_t(a) + int64_t(b) - int64_t(c), last_new_};
    int best = int(std::min_element(score_, score_ + kPredictors) - score_);
    const int gap = gap_class(magnitude_of(int64_t(a) - int64_t(b)));
    const int free_gap = gap_class(ids.free_in(int64_t(std::min(a, b)) + 1, int64_t(std::max(a, b)) - 1));
    // Far apart gate ids: a new vertex is usually near one of them, rarely between.
    if (best < 2 && free_gap >= kSideGap) {
      const bool use_min = !Io::kDecoding && magnitude_of(ids.rank(p[1], x)) < magnitude_of(ids.rank(p[0], x));
      best = io.bit(m.far_side[free_gap][b > a], use_min);
    }
    const int ctx = best * kGapClasses + gap;
    const int sign_ctx = best * 9 + 3 * ((b > a) + (b >= a)) + (last_rank_ > 0) + (last_rank_ >= 0);
    const int64_t rank = io.integer(m.ints, ctx, sign_ctx, Io::kDecoding ? 0 : ids.rank(p[best], x));
    if (!ids.unrank(p[best], rank, out)) return fail(error, "face vertex rank names no id");
    int64_t ranks[kPredictors];
    for (int i = 0; i < kPredictors; ++i) ranks[i] = ids.rank(p[i], *out);
    if (!accept(region, *out, true, error)) return false;
    for (int i = 0; i < kPredictors; ++i)
      score_[i] = score_[i] - (score_[i] >> 7) + 16 * uint32_t(bit_length(magnitude_of(ranks[i])));
    last_new_ = *out;
    last_rank_ = rank;
    return true;
  }

 private:
  uint32_t score_[kPredictors] = {};
  int64_t last_new_ = 0;
  int64_t last_rank_ = 0;
};

// The breadth-first traversal both sides run (format_spec/dcrv.md 6.3). Encoding, `list`
// holds the T triangles to code; decoding, they are appended to it. Every id is below
// `bound` (the vertex count; a decoder rejects any other as soon as it is read).
template <class Io>
bool traverse(Io& io, uint64_t T, uint32_t bound, std::vector<uint32_t>* list, std::string* error) {
  Models m;
  Region region(bound);
  region.reserve(size_t(std::min<uint64_t>(T, 1u << 16)));  // a few MB at most before any decoding
  NewIds new_ids;
  int64_t ref = 0;  // the last id coded at a component start
  uint64_t head = 0, n = 0;
  // The encoder's answer for corner c of triangle t (unused when decoding).
  auto truth = [&](uint64_t t, int c) { return Io::kDecoding ? 0u : (*list)[size_t(3 * t) + c]; };
  auto emit = [&](const uint32_t* tri) {
    if (Io::kDecoding) list->insert(list->end(), tri, tri + 3);
    region.add_triangle(tri);
    ++n;
  };
  while (n < T) {
    if (io.overrun()) return fail(error, "face stream is truncated");
    if (head == n) {  // nothing left to expand: a component starts with explicit ids
      uint32_t tri[3];
      for (int c = 0; c < 3; ++c) {
        const uint32_t x = truth(n, c);
        const bool is_new = io.bit(m.start_new, !region.seen(x));
        const int64_t id = ref + io.integer(m.ints, is_new ? kCtxStartNew : kCtxStartSeen, kSignOther, int64_t(x) - ref);
        if (!accept(region, id, is_new, error)) return false;
        if (is_new) new_ids.starts_at(id);
        tri[c] = uint32_t(id);
        ref = id;
      }
      emit(tri);
    }
    const uint32_t gate[3] = {(*list)[size_t(3 * head)], (*list)[size_t(3 * head + 1)], (*list)[size_t(3 * head + 2)]};
    for (int e = 0; e < 3 && n < T; ++e) {
      const uint32_t a = gate[e], b = gate[(e + 1) % 3], c = gate[(e + 2) % 3];
      const bool fits = !Io::kDecoding && truth(n, 0) == b && truth(n, 1) == a;
      if (!io.bit(m.follows[2 * e + region.has_edge(b, a)], fits)) continue;
      const uint32_t x = truth(n, 2);
      uint32_t cand[kMaxCandidates] = {};  // listed() reads all of it
      int k_a = 0;
      const int k = region.candidates(a, b, cand, &k_a);
      const int at = Io::kDecoding ? -1 : int(std::find(cand, cand + k, x) - cand);
      const int fa = region.fan(a), fb = region.fan(b);
      const int sides = (k_a > 0) + 2 * (k > k_a);
      int64_t id;
      if (k > 0 && io.bit(m.in_list[sides - 1][fa][fb], at < k)) {
        int i = 0;
        while (i + 1 < k && io.bit(i == 0 ? m.first_index[fa][fb] : m.index[i > 1], at > i)) ++i;
        id = cand[i];
      } else if (io.bit(m.is_new[k > 0], !region.seen(x))) {
        uint32_t fresh = 0;
        if (!new_ids.code(io, m, region, a, b, c, x, &fresh, error)) return false;
        id = fresh;
      } else {
        id = a + io.integer(m.ints, kCtxFar, kSignOther, int64_t(x) - a);
        if (!accept(region, id, false, error)) return false;
      }
      const uint32_t tri[3] = {b, a, uint32_t(id)};
      emit(tri);
    }
    ++head;
  }
  return true;
}

inline uint64_t triangle_bound(size_t stream_bytes) {
  return kCompactFreeTriangles + kCompactTrianglesPerByte * uint64_t(stream_bytes);
}

}  // namespace faces_compact_walk
}  // namespace dcurve
