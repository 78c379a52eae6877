#include "encoder/rate/cluster_plan.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "codec/common/motion_compensation.h"
#include "encoder/rate/plan_steps.h"

namespace dcurve {
namespace {

// Residual cost model of the per-cluster choice: adaptive bits per (context, exponent
// class), learnt from the residuals already chosen (older frames decay), plus the raw
// mantissa bits. Contexts as in residual_plan.cpp: neighbour class (5) x axis class (3).
class CostTable {
 public:
  static constexpr int kContexts = 15, kClasses = kResidualClasses;
  CostTable() : counts_(size_t(kContexts) * kClasses), bits_(counts_.size()) {
    // Prior: what residual_cost says, as a few pseudo-observations per context.
    for (int c = 0; c < kContexts; ++c)
      for (int k = 0; k < kClasses; ++k) counts_[size_t(c) * kClasses + size_t(k)] = 8 * std::exp2(-prior_bits(k));
    rebuild();
  }
  double cost(int ctx, int64_t r) const {
    int e;
    const int k = residual_class(r, &e);
    return bits_[size_t(ctx) * kClasses + size_t(k)] + e;
  }
  void add(int ctx, int64_t r) {
    int e;
    counts_[size_t(ctx) * kClasses + size_t(residual_class(r, &e))] += 1;
  }
  // Halves what was learnt before (statistics drift between frames), then recomputes bits.
  void next_frame() {
    rebuild();
    for (double& c : counts_) c *= 0.5;
  }

 private:
  static double prior_bits(int k) { return k == 0 ? 1 : 3 + 2 * ((k - 1) / 2); }
  void rebuild() {
    for (int c = 0; c < kContexts; ++c) {
      const double* h = &counts_[size_t(c) * kClasses];
      double total = 0;
      for (int k = 0; k < kClasses; ++k) total += h[k] + 0.01;
      for (int k = 0; k < kClasses; ++k) bits_[size_t(c) * kClasses + size_t(k)] = -std::log2((h[k] + 0.01) / total);
    }
  }
  std::vector<double> counts_, bits_;
};

// Solves the 4x4 system n w = b (symmetric positive semi-definite) by Gaussian
// elimination with partial pivoting; false when singular.
bool solve4(double n[4][4], double b[4], double w[4]) {
  int idx[4] = {0, 1, 2, 3};
  for (int col = 0; col < 4; ++col) {
    int piv = col;
    for (int r = col + 1; r < 4; ++r)
      if (std::fabs(n[r][col]) > std::fabs(n[piv][col])) piv = r;
    if (std::fabs(n[piv][col]) < 1e-12) return false;
    std::swap(n[piv], n[col]);
    std::swap(b[piv], b[col]);
    std::swap(idx[piv], idx[col]);
    for (int r = col + 1; r < 4; ++r) {
      const double f = n[r][col] / n[col][col];
      for (int k = col; k < 4; ++k) n[r][k] -= f * n[col][k];
      b[r] -= f * b[col];
    }
  }
  for (int r = 3; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < 4; ++k) s -= n[r][k] * w[k];
    w[r] = s / n[r][r];
  }
  return true;
}

int32_t quantize(double v, int32_t limit) {
  const double r = std::nearbyint(v);
  return int32_t(std::max<double>(-limit, std::min<double>(limit, std::isfinite(r) ? r : 0)));
}

// Pool entries (candidate predictors of the frame) for axes 0, 1, 2.
using Triple = std::array<uint32_t, 3>;

}  // namespace

MotionTransform fit_motion(const ResidualLayer& layer, const float* target, const int32_t* ref, const Traversal& trav,
                           uint32_t begin, uint32_t end) {
  int64_t c[3];
  cluster_centre(ref, trav, begin, end, c);
  // Unknowns per output axis: the deviation of the matrix row from the identity and the
  // translation, so a ridge term pulls ill-conditioned (flat, tiny) clusters to identity.
  double n[4][4] = {}, rhs[3][4] = {};
  for (uint32_t pos = begin; pos < end; ++pos) {
    const uint32_t v = trav.order[pos];
    double z[4];
    for (int a = 0; a < 3; ++a) z[a] = double(int64_t(ref[size_t(v) * 3 + size_t(a)]) - c[a]);
    z[3] = 1;
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 4; ++k) n[i][k] += z[i] * z[k];
    for (int a = 0; a < 3; ++a) {
      const double y = (double(target[size_t(v) * 3 + size_t(a)]) - layer.origin[a]) / layer.step - double(c[a]) - z[a];
      for (int i = 0; i < 4; ++i) rhs[a][i] += z[i] * y;
    }
  }
  const double ridge = 1e-3 * (n[0][0] + n[1][1] + n[2][2]) + 1e-9;
  MotionTransform t;
  for (int a = 0; a < 3; ++a) {
    double m[4][4], b[4], w[4];
    std::copy(&n[0][0], &n[0][0] + 16, &m[0][0]);
    for (int i = 0; i < 3; ++i) m[i][i] += ridge;
    std::copy(rhs[a], rhs[a] + 4, b);
    if (!solve4(m, b, w)) continue;
    for (int k = 0; k < 3; ++k) t.row[a].m[k] = quantize(w[k] * double(kMotionOne), kMaxMotionMatrix);
    t.row[a].t = quantize(w[3], kMaxMotionShift);
  }
  return t;
}

PredictorPlan choose_cluster_plan(const Model& model, const std::vector<std::vector<float>>& frames, double radius,
                                  const std::vector<uint32_t>& order, uint32_t cluster_size, uint32_t motion_block,
                                  uint32_t max_candidates, std::vector<int32_t>* q, const ResidualOptions& options,
                                  const ResidualPlanOptions& po) {
  const uint32_t V = model.meta.vertex_count, F = model.meta.frame_count;
  const uint32_t S = std::max(cluster_size, 1u), clusters = cluster_count(V, S), M = std::max(motion_block, 1u);
  max_candidates = std::max(1u, std::min(max_candidates, kMaxCandidates));
  const size_t stride = size_t(V) * 3;
  Traversal owned;
  const Traversal& trav = traversal_for(model, options, &owned);
  PredictorPlan plan;
  plan.order = order;
  plan.cluster_size = S;
  plan.motion_block = M;
  const uint32_t blocks = motion_block_count(V, plan);
  // Share of a motion map's bits charged to each cluster using it: as if a quarter of the
  // block's clusters used it.
  const double motion_share = std::min(1.0, 4.0 / M);
  plan.frames.resize(F);
  std::vector<uint8_t> decoded(F, 0), magnitude(stride);
  std::vector<int64_t> base, plane;
  std::vector<AxisRun> scratch_runs;
  std::vector<int32_t> orig(stride), best_values;
  std::vector<std::pair<int, int64_t>> trial_res, best_res;  // (context, residual) of the cluster
  CostTable table;
  SpatialWeightsCache geometry(options.weights_source);
  for (uint32_t f : order) {
    int32_t* qf = q->data() + size_t(f) * stride;
    const float* input = frames[f].data();
    const std::vector<AxisRun>& runs =
        po.snap ? frame_axis_runs(po, model.residual, input, V, radius, f, &scratch_runs) : scratch_runs;
    std::copy(qf, qf + stride, orig.begin());
    // The pool: the frame-wide candidates, and a motion-compensated twin of every Reference.
    ResidualPlanOptions with_references = po;
    with_references.kinds |= 1u << int(PredictorKind::Reference);
    // Every geometry frame the pool can name is a nearest decoded frame or one of these
    // poses, so no frame's candidates exceed what a decoder accepts.
    with_references.extra_references = std::min(po.extra_references, kMaxGeometryFrames - 2);
    std::vector<PredictorChoice> pool;
    for (const PredictorChoice& c : candidates_for(*q, V, f, decoded, options, with_references)) {
      if (c.kind != PredictorKind::Reference || po.kinds >> int(PredictorKind::Reference) & 1) pool.push_back(c);
      if (c.kind == PredictorKind::Reference && po.kinds >> int(PredictorKind::Motion) & 1)
        pool.push_back({PredictorKind::Motion, c.r0, 0, c.spatial, c.g});
    }
    if (pool.empty()) pool.push_back({PredictorKind::None, 0, 0, SpatialMode::Off});
    // Candidate c's prediction of vertex u on axis a at base[(c * V + u) * 3 + a]: a vertex's
    // three axes share a cache line, which the evaluations below read together.
    base.resize(pool.size() * stride);
    plane.resize(V);
    for (size_t c = 0; c < pool.size(); ++c)
      for (int a = 0; a < 3; ++a) {
        base_prediction(pool[c], f, a, V, q->data(), options, plane.data());
        int64_t* out = &base[c * stride + size_t(a)];
        for (uint32_t u = 0; u < V; ++u) out[size_t(u) * 3] = plane[u];
      }
    // Motion maps (and the block centres they apply around) per motion block and
    // reference frame, computed once.
    struct BlockMap {
      uint32_t r0;
      MotionTransform map;
      int64_t centre[3];
    };
    std::vector<std::vector<BlockMap>> maps(blocks);
    auto map_for = [&](uint32_t b, uint32_t r0) -> const BlockMap& {
      for (const BlockMap& m : maps[b])
        if (m.r0 == r0) return m;
      const uint32_t begin = b * M * S, end = uint32_t(std::min<uint64_t>(V, (uint64_t(b) + 1) * M * S));
      const int32_t* ref = q->data() + size_t(r0) * stride;
      BlockMap m{r0, fit_motion(model.residual, input, ref, trav, begin, end), {}};
      cluster_centre(ref, trav, begin, end, m.centre);
      maps[b].push_back(m);
      return maps[b].back();
    };
    // A choice is a pool entry per axis; at first each entry on all three axes.
    std::vector<Triple> allowed;
    for (uint32_t c = 0; c < pool.size(); ++c) allowed.push_back({c, c, c});
    std::vector<Triple> chosen(clusters);
    // Greedy over the clusters in decoding order; a second round when more choices were
    // used than a frame may keep, restricted to the most used ones.
    std::vector<std::pair<int, int64_t>> frame_res;
    for (int round = 0; round < 2; ++round) {
      std::copy(orig.begin(), orig.end(), qf);
      frame_res.clear();
      Triple prev = {UINT32_MAX, UINT32_MAX, UINT32_MAX};
      // Places in `allowed`, most wins in this round first (equal counts in the order they
      // reached them): the evaluation order after the previous cluster's choice.
      std::vector<uint32_t> wins(allowed.size(), 0);
      std::vector<size_t> by_wins(allowed.size());
      for (size_t i = 0; i < by_wins.size(); ++i) by_wins[i] = i;
      std::vector<size_t> places;
      MotionRow prev_row[3];
      std::vector<std::vector<Triple>> paid(blocks);  // choices whose map the block has coded
      for (uint32_t k = 0; k < clusters; ++k) {
        const uint32_t begin = k * S, end = std::min(V, begin + S), b = k / M;
        double best = HUGE_VAL;
        // Estimated bits of choice t on cluster k (stops early beyond `bound`); per-axis
        // bits of a complete evaluation go to axis_bits.
        auto evaluate = [&](const Triple& t, double bound, double axis_bits[3]) {
          const PredictorChoice choice[3] = {pool[t[0]], pool[t[1]], pool[t[2]]};
          // Signalling: repeating the previous cluster's choice costs a flag, switching the
          // flag and an index. 2 bits for a repeat (more than the flag costs) gives smaller
          // files: it offsets the index cost's overestimate over the whole pool, of which at
          // most max_candidates stay.
          double bits = allowed.size() < 2 ? 0 : t == prev ? 2 : 1 + std::log2(double(allowed.size()));
          MotionRow rows[3];
          int64_t centre[3][3];
          const int32_t* ref[3];
          const int32_t* weights[3];
          geometry.for_choice(trav, q->data(), choice, weights);
          const bool map_paid = std::find(paid[b].begin(), paid[b].end(), t) != paid[b].end();
          for (int a = 0; a < 3; ++a) {
            ref[a] = q->data() + size_t(choice[a].r0) * stride;
            if (choice[a].kind != PredictorKind::Motion) continue;
            const BlockMap& m = map_for(b, choice[a].r0);
            rows[a] = m.map.row[a];
            std::copy(m.centre, m.centre + 3, centre[a]);
            // The map is coded once per block; charging only the first cluster that uses
            // it would never let a small cluster pay for it, so every user pays a share.
            if (map_paid) continue;
            for (int e = 0; e < 4; ++e)
              bits += motion_share * (1 + residual_cost(int64_t(e < 3 ? rows[a].m[e] : rows[a].t) -
                                                        (e < 3 ? prev_row[a].m[e] : prev_row[a].t)));
          }
          auto base_of = [&](uint32_t u, int a) -> int64_t {
            if (choice[a].kind == PredictorKind::Motion)
              return motion_prediction(rows[a], a, centre[a], ref[a] + size_t(u) * 3);
            return base[size_t(t[size_t(a)]) * stride + size_t(u) * 3 + size_t(a)];
          };
          std::fill(axis_bits, axis_bits + 3, HUGE_VAL);
          double per_axis[3] = {0, 0, 0};
          trial_res.clear();
          for (uint32_t pos = begin; pos < end; ++pos) {
            if (bits >= bound) return bits;
            const uint32_t v = trav.order[pos];
            int32_t* qv = qf + size_t(v) * 3;
            std::copy(&orig[size_t(v) * 3], &orig[size_t(v) * 3] + 3, qv);
            int64_t pred[3];
            vertex_prediction(choice, trav, pos, qf, base_of, pred, weights);
            if (po.snap)
              snap_vertex(model.residual, input + size_t(v) * 3, &runs[size_t(v) * 3], radius, po.distance_weight, pred,
                          qv);
            uint8_t axis_max = 0;
            int classes[3];
            neighbour_classes(trav, pos, magnitude, classes);
            for (int a = 0; a < 3; ++a) {
              const int64_t r = int64_t(qv[a]) - pred[a];
              const int ctx = classes[a] * 3 + std::min<uint8_t>(axis_max, 2);
              const double c = table.cost(ctx, r);
              bits += c;
              per_axis[a] += c;
              trial_res.emplace_back(ctx, r);
              magnitude[size_t(v) * 3 + size_t(a)] = uint8_t(std::min<int64_t>(r < 0 ? -r : r, 255));
              axis_max = std::max(axis_max, magnitude[size_t(v) * 3 + size_t(a)]);
            }
          }
          std::copy(per_axis, per_axis + 3, axis_bits);
          return bits;
        };
        // The winner is the least bits, ties to the earliest place in `allowed` (the mix comes
        // after all), whatever order the entries are evaluated in: an entry before the best
        // so far must exceed its bits to stop, one after it only reach them.
        size_t best_place = SIZE_MAX;
        auto consider = [&](const Triple& t, size_t place, double axis_bits[3]) {
          const bool earlier = place < best_place;
          const double bits = evaluate(t, earlier ? std::nextafter(best, HUGE_VAL) : best, axis_bits);
          if (bits > best || (bits == best && !earlier)) return;
          best = bits;
          best_place = place;
          chosen[k] = t;
          best_values.clear();
          for (uint32_t pos = begin; pos < end; ++pos)
            best_values.insert(best_values.end(), qf + size_t(trav.order[pos]) * 3, qf + size_t(trav.order[pos]) * 3 + 3);
          best_res.swap(trial_res);
        };
        // Per axis, the entry whose complete evaluation cost least there: their mix is
        // tried too (the snapped grid point couples the axes, so it is evaluated anew).
        double best_axis[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
        Triple mix = allowed[0];
        // Evaluated first: the previous cluster's choice, then the round's most frequent
        // winners. A cheap winner found early stops the others sooner, so far fewer vertices
        // are evaluated than in allowed order. Only the mix depends on the order, through
        // which evaluations complete.
        places.clear();
        const size_t first = size_t(std::find(allowed.begin(), allowed.end(), prev) - allowed.begin());
        if (first < allowed.size()) places.push_back(first);
        for (size_t place : by_wins)
          if (place != first) places.push_back(place);
        for (size_t place : places) {
          const Triple& t = allowed[place];
          double axis_bits[3];
          consider(t, place, axis_bits);
          for (int a = 0; a < 3; ++a)
            if (axis_bits[a] < best_axis[a]) {
              best_axis[a] = axis_bits[a];
              mix[size_t(a)] = t[size_t(a)];
            }
        }
        if (round == 0 && std::find(allowed.begin(), allowed.end(), mix) == allowed.end()) {
          double axis_bits[3];
          consider(mix, allowed.size(), axis_bits);
        }
        // Commit the winner: its values, and the magnitudes later contexts read.
        for (uint32_t pos = begin; pos < end; ++pos) {
          const uint32_t v = trav.order[pos];
          std::copy(&best_values[size_t(pos - begin) * 3], &best_values[size_t(pos - begin) * 3] + 3, qf + size_t(v) * 3);
          for (int a = 0; a < 3; ++a) {
            const int64_t r = best_res[size_t(pos - begin) * 3 + size_t(a)].second;
            magnitude[size_t(v) * 3 + size_t(a)] = uint8_t(std::min<int64_t>(r < 0 ? -r : r, 255));
          }
        }
        prev = chosen[k];
        if (best_place < allowed.size()) {
          size_t i = size_t(std::find(by_wins.begin(), by_wins.end(), best_place) - by_wins.begin());
          ++wins[best_place];
          for (; i > 0 && wins[by_wins[i - 1]] < wins[by_wins[i]]; --i) std::swap(by_wins[i - 1], by_wins[i]);
        }
        if (std::find(paid[b].begin(), paid[b].end(), prev) == paid[b].end()) {
          bool motion = false;
          for (int a = 0; a < 3; ++a)
            if (pool[prev[size_t(a)]].kind == PredictorKind::Motion) {
              motion = true;
              prev_row[a] = map_for(b, pool[prev[size_t(a)]].r0).map.row[a];
            }
          if (motion) paid[b].push_back(prev);
        }
        frame_res.insert(frame_res.end(), best_res.begin(), best_res.end());
      }
      // The choices used, most used first.
      std::vector<std::pair<Triple, uint32_t>> uses;
      for (const Triple& t : chosen) {
        auto it = std::find_if(uses.begin(), uses.end(), [&](const auto& u) { return u.first == t; });
        if (it == uses.end()) uses.emplace_back(t, 1);
        else ++it->second;
      }
      std::stable_sort(uses.begin(), uses.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
      allowed.clear();
      for (const auto& u : uses) allowed.push_back(u.first);
      if (allowed.size() <= max_candidates) break;
      allowed.resize(max_candidates);
    }
    // The frame's candidates: the choices used, most used first (the second round never
    // uses more than max_candidates, so the loop always ends through the break).
    const std::vector<Triple>& used = allowed;
    FramePredictors& fp = plan.frames[f];
    bool any_motion = false;
    for (const Triple& t : used) {
      fp.candidates.push_back({pool[t[0]], pool[t[1]], pool[t[2]]});
      for (uint32_t c : t) any_motion = any_motion || pool[c].kind == PredictorKind::Motion;
    }
    auto index_of = [&](const Triple& t) { return size_t(std::find(used.begin(), used.end(), t) - used.begin()); };
    if (used.size() > 1)
      for (const Triple& t : chosen) fp.cluster_candidate.push_back(uint8_t(index_of(t)));
    if (any_motion) {
      fp.transforms.assign(size_t(blocks) * used.size(), MotionTransform());
      for (uint32_t k = 0; k < clusters; ++k)
        for (int a = 0; a < 3; ++a) {
          const PredictorChoice& c = pool[chosen[k][size_t(a)]];
          if (c.kind == PredictorKind::Motion)
            fp.transforms[size_t(k / M) * used.size() + index_of(chosen[k])].row[a] = map_for(k / M, c.r0).map.row[a];
        }
    }
    for (const auto& [ctx, r] : frame_res) table.add(ctx, r);
    table.next_frame();
    decoded[f] = 1;
  }
  return plan;
}

}  // namespace dcurve
