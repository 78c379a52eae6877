#include "encoder/rate/cluster_plan.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "codec/common/motion_compensation.h"
#include "encoder/rate/plan_steps.h"
#include "encoder/work_meter.h"

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

namespace {

// A motion map of one block of clusters from reference frame r0, and the centre it applies around.
struct BlockMap {
  uint32_t r0;
  MotionTransform map;
  int64_t centre[3];
};

// One greedy pass over a frame's clusters: what the choice of each cluster reads of the
// ones before it.
struct Round {
  Triple prev = {UINT32_MAX, UINT32_MAX, UINT32_MAX};  // the previous cluster's choice
  // Wins per place in `allowed`, and the places by wins (equal counts in the order they
  // reached them): the order the next cluster evaluates them in.
  std::vector<uint32_t> wins;
  std::vector<size_t> by_wins;
  MotionRow prev_row[3];                     // the last motion map coded, per axis
  std::vector<std::vector<Triple>> paid;     // per block, the choices whose map it has coded
  std::vector<std::pair<int, int64_t>> res;  // (context, residual) of every committed cluster
};

// The best choice found so far for one cluster, and the per-axis bests whose mix is tried.
struct ClusterBest {
  double bits = HUGE_VAL;
  size_t place = SIZE_MAX;
  std::vector<int32_t> values;               // the cluster's grid values, by position
  std::vector<std::pair<int, int64_t>> res;  // its (context, residual) pairs
  double axis_bits[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
  Triple mix{};
};

// The per-cluster plan of one chunk, frame by frame in coding order. A frame builds its
// pool of candidates and their base predictions, then chooses each cluster greedily
// (evaluate, consider, commit), in a second round restricted to the most used choices when
// more were used than a frame may keep, and records the result.
class ClusterPlanner {
 public:
  ClusterPlanner(const Model& model, const std::vector<std::vector<float>>& frames, double radius,
                 uint32_t cluster_size, uint32_t motion_block, uint32_t max_candidates, std::vector<int32_t>* q,
                 const ResidualOptions& options, const ResidualPlanOptions& po);
  PredictorPlan take_plan() { return std::move(plan_); }
  void plan_frame(uint32_t f);

 private:
  void build_pool(uint32_t f);
  void fill_bases(uint32_t f);
  const BlockMap& map_for(uint32_t b, uint32_t r0);
  double signalling_bits(const Triple& t, const Round& round) const;
  double evaluate(uint32_t k, const Triple& t, double bound, const Round& round, double axis_bits[3]);
  void consider(uint32_t k, const Triple& t, size_t place, const Round& round, ClusterBest* best);
  void choose_cluster(uint32_t k, int round_index, Round* round);
  void commit_cluster(uint32_t k, const ClusterBest& best, Round* round);
  void run_round(int round_index);
  bool restrict_to_most_used();
  void record_frame(uint32_t f);

  const Model& model_;
  const std::vector<std::vector<float>>& frames_;
  const double radius_;
  std::vector<int32_t>* q_;
  const ResidualOptions& options_;
  const ResidualPlanOptions& po_;
  Traversal owned_;
  const Traversal& trav_;
  const uint32_t V_, S_, M_, clusters_, max_candidates_;
  const size_t stride_;
  uint32_t blocks_ = 0;
  // Share of a motion map's bits charged to each cluster using it: as if a quarter of the
  // block's clusters used it.
  const double motion_share_;
  PredictorPlan plan_;
  std::vector<uint8_t> decoded_, magnitude_;
  CostTable table_;
  SpatialWeightsCache geometry_;
  // The frame being planned.
  int32_t* qf_ = nullptr;
  const float* input_ = nullptr;
  const std::vector<AxisRun>* runs_ = nullptr;
  std::vector<AxisRun> scratch_runs_;
  std::vector<int32_t> orig_;  // its values before planning
  std::vector<PredictorChoice> pool_;
  // Candidate c's prediction of vertex u on axis a at base_[(c * V + u) * 3 + a]: a vertex's
  // three axes share a cache line, which the evaluations read together.
  std::vector<int64_t> base_, plane_;
  std::vector<std::vector<BlockMap>> maps_;  // per motion block, computed once per reference
  std::vector<Triple> allowed_, chosen_;
  std::vector<std::pair<int, int64_t>> trial_res_, frame_res_;
};

ClusterPlanner::ClusterPlanner(const Model& model, const std::vector<std::vector<float>>& frames, double radius,
                               uint32_t cluster_size, uint32_t motion_block, uint32_t max_candidates,
                               std::vector<int32_t>* q, const ResidualOptions& options, const ResidualPlanOptions& po)
    : model_(model), frames_(frames), radius_(radius), q_(q), options_(options), po_(po),
      trav_(traversal_for(model, options, &owned_)), V_(model.meta.vertex_count), S_(std::max(cluster_size, 1u)),
      M_(std::max(motion_block, 1u)), clusters_(cluster_count(V_, S_)),
      max_candidates_(std::max(1u, std::min(max_candidates, kMaxCandidates))), stride_(size_t(V_) * 3),
      motion_share_(std::min(1.0, 4.0 / M_)), decoded_(model.meta.frame_count, 0), magnitude_(stride_),
      geometry_(options.weights_source), orig_(stride_) {
  plan_.cluster_size = S_;
  plan_.motion_block = M_;
  blocks_ = motion_block_count(V_, plan_);
  plan_.frames.resize(model.meta.frame_count);
}

// The pool: the frame-wide candidates, and a motion-compensated twin of every Reference.
void ClusterPlanner::build_pool(uint32_t f) {
  ResidualPlanOptions with_references = po_;
  with_references.kinds |= 1u << int(PredictorKind::Reference);
  // Every geometry frame the pool can name is a nearest decoded frame or one of these
  // poses, so no frame's candidates exceed what a decoder accepts.
  with_references.extra_references = std::min(po_.extra_references, kMaxGeometryFrames - 2);
  pool_.clear();
  for (const PredictorChoice& c : candidates_for(*q_, V_, f, decoded_, options_, with_references)) {
    if (c.kind != PredictorKind::Reference || po_.kinds >> int(PredictorKind::Reference) & 1) pool_.push_back(c);
    if (c.kind == PredictorKind::Reference && po_.kinds >> int(PredictorKind::Motion) & 1)
      pool_.push_back({PredictorKind::Motion, c.r0, 0, c.spatial, c.g});
  }
  if (pool_.empty()) pool_.push_back({PredictorKind::None, 0, 0, SpatialMode::Off});
}

void ClusterPlanner::fill_bases(uint32_t f) {
  base_.resize(pool_.size() * stride_);
  plane_.resize(V_);
  for (size_t c = 0; c < pool_.size(); ++c)
    for (int a = 0; a < 3; ++a) {
      base_prediction(pool_[c], f, a, V_, q_->data(), options_, plane_.data());
      int64_t* out = &base_[c * stride_ + size_t(a)];
      for (uint32_t u = 0; u < V_; ++u) out[size_t(u) * 3] = plane_[u];
    }
}

const BlockMap& ClusterPlanner::map_for(uint32_t b, uint32_t r0) {
  for (const BlockMap& m : maps_[b])
    if (m.r0 == r0) return m;
  const uint32_t begin = b * M_ * S_, end = uint32_t(std::min<uint64_t>(V_, (uint64_t(b) + 1) * M_ * S_));
  const int32_t* ref = q_->data() + size_t(r0) * stride_;
  BlockMap m{r0, fit_motion(model_.residual, input_, ref, trav_, begin, end), {}};
  cluster_centre(ref, trav_, begin, end, m.centre);
  maps_[b].push_back(m);
  return maps_[b].back();
}

// Signalling: repeating the previous cluster's choice costs a flag, switching the flag and
// an index. 2 bits for a repeat (more than the flag costs) gives smaller files: it offsets
// the index cost's overestimate over the whole pool, of which at most max_candidates stay.
double ClusterPlanner::signalling_bits(const Triple& t, const Round& round) const {
  return allowed_.size() < 2 ? 0 : t == round.prev ? 2 : 1 + std::log2(double(allowed_.size()));
}

// Estimated bits of choice t on cluster k, stopping early beyond `bound`; the per-axis bits
// of a complete evaluation go to axis_bits (HUGE_VAL when stopped). Leaves the trial's
// values in the frame and its (context, residual) pairs in trial_res_.
double ClusterPlanner::evaluate(uint32_t k, const Triple& t, double bound, const Round& round,
                                double axis_bits[3]) {
  const uint32_t begin = k * S_, end = std::min(V_, begin + S_), b = k / M_;
  const PredictorChoice choice[3] = {pool_[t[0]], pool_[t[1]], pool_[t[2]]};
  double bits = signalling_bits(t, round);
  MotionRow rows[3];
  int64_t centre[3][3];
  const int32_t* ref[3];
  const int32_t* weights[3];
  geometry_.for_choice(trav_, q_->data(), choice, weights);
  const bool map_paid = std::find(round.paid[b].begin(), round.paid[b].end(), t) != round.paid[b].end();
  for (int a = 0; a < 3; ++a) {
    ref[a] = q_->data() + size_t(choice[a].r0) * stride_;
    if (choice[a].kind != PredictorKind::Motion) continue;
    const BlockMap& m = map_for(b, choice[a].r0);
    rows[a] = m.map.row[a];
    std::copy(m.centre, m.centre + 3, centre[a]);
    // The map is coded once per block; charging only the first cluster that uses it would
    // never let a small cluster pay for it, so every user pays a share.
    if (map_paid) continue;
    const MotionRow& p = round.prev_row[a];
    for (int e = 0; e < 4; ++e)
      bits += motion_share_ * (1 + residual_cost(int64_t(e < 3 ? rows[a].m[e] : rows[a].t) - (e < 3 ? p.m[e] : p.t)));
  }
  auto base_of = [&](uint32_t u, int a) -> int64_t {
    if (choice[a].kind == PredictorKind::Motion) return motion_prediction(rows[a], a, centre[a], ref[a] + size_t(u) * 3);
    return base_[size_t(t[size_t(a)]) * stride_ + size_t(u) * 3 + size_t(a)];
  };
  std::fill(axis_bits, axis_bits + 3, HUGE_VAL);
  double per_axis[3] = {0, 0, 0};
  trial_res_.clear();
  for (uint32_t pos = begin; pos < end; ++pos) {
    if (bits >= bound) return bits;
    const uint32_t v = trav_.order[pos];
    int32_t* qv = qf_ + size_t(v) * 3;
    std::copy(&orig_[size_t(v) * 3], &orig_[size_t(v) * 3] + 3, qv);
    int64_t pred[3];
    vertex_prediction(choice, trav_, pos, qf_, base_of, pred, weights);
    if (po_.snap)
      snap_vertex(model_.residual, input_ + size_t(v) * 3, &(*runs_)[size_t(v) * 3], radius_, po_.distance_weight,
                  pred, qv);
    uint8_t axis_max = 0;
    int classes[3];
    neighbour_classes(trav_, pos, magnitude_, classes);
    for (int a = 0; a < 3; ++a) {
      const int64_t r = int64_t(qv[a]) - pred[a];
      const int ctx = classes[a] * 3 + std::min<uint8_t>(axis_max, 2);
      const double c = table_.cost(ctx, r);
      bits += c;
      per_axis[a] += c;
      trial_res_.emplace_back(ctx, r);
      magnitude_[size_t(v) * 3 + size_t(a)] = uint8_t(std::min<int64_t>(r < 0 ? -r : r, 255));
      axis_max = std::max(axis_max, magnitude_[size_t(v) * 3 + size_t(a)]);
    }
  }
  std::copy(per_axis, per_axis + 3, axis_bits);
  return bits;
}

// Evaluates t (at `place` in allowed_, or past its end for the mix) and keeps it as the
// cluster's best when it costs least, ties to the earliest place (the mix comes after all),
// whatever order the entries are evaluated in: an entry before the best so far must exceed
// its bits to stop, one after it only reach them. Per axis, the entry whose complete
// evaluation cost least there becomes part of the mix.
void ClusterPlanner::consider(uint32_t k, const Triple& t, size_t place, const Round& round, ClusterBest* best) {
  const bool earlier = place < best->place;
  double axis_bits[3];
  const double bits = evaluate(k, t, earlier ? std::nextafter(best->bits, HUGE_VAL) : best->bits, round, axis_bits);
  if (place < allowed_.size())
    for (int a = 0; a < 3; ++a)
      if (axis_bits[a] < best->axis_bits[a]) {
        best->axis_bits[a] = axis_bits[a];
        best->mix[size_t(a)] = t[size_t(a)];
      }
  if (bits > best->bits || (bits == best->bits && !earlier)) return;
  best->bits = bits;
  best->place = place;
  chosen_[k] = t;
  const uint32_t begin = k * S_, end = std::min(V_, begin + S_);
  best->values.clear();
  for (uint32_t pos = begin; pos < end; ++pos)
    best->values.insert(best->values.end(), qf_ + size_t(trav_.order[pos]) * 3, qf_ + size_t(trav_.order[pos]) * 3 + 3);
  best->res.swap(trial_res_);
}

// Chooses cluster k's entry: the previous cluster's choice first, then the round's most
// frequent winners (a cheap winner found early stops the others sooner, so far fewer
// vertices are evaluated than in allowed order; only the mix depends on the order, through
// which evaluations complete), then in the first round the per-axis mix (the snapped grid
// point couples the axes, so it is evaluated anew).
void ClusterPlanner::choose_cluster(uint32_t k, int round_index, Round* round) {
  ClusterBest best;
  best.mix = allowed_[0];
  const size_t first = size_t(std::find(allowed_.begin(), allowed_.end(), round->prev) - allowed_.begin());
  if (first < allowed_.size()) consider(k, allowed_[first], first, *round, &best);
  for (size_t place : round->by_wins)
    if (place != first) consider(k, allowed_[place], place, *round, &best);
  if (round_index == 0 && std::find(allowed_.begin(), allowed_.end(), best.mix) == allowed_.end())
    consider(k, best.mix, allowed_.size(), *round, &best);
  commit_cluster(k, best, round);
}

// Commits the winner: its values, the magnitudes later contexts read, its win, and the
// motion map its block now has coded.
void ClusterPlanner::commit_cluster(uint32_t k, const ClusterBest& best, Round* round) {
  const uint32_t begin = k * S_, end = std::min(V_, begin + S_), b = k / M_;
  for (uint32_t pos = begin; pos < end; ++pos) {
    const uint32_t v = trav_.order[pos];
    std::copy(&best.values[size_t(pos - begin) * 3], &best.values[size_t(pos - begin) * 3] + 3, qf_ + size_t(v) * 3);
    for (int a = 0; a < 3; ++a) {
      const int64_t r = best.res[size_t(pos - begin) * 3 + size_t(a)].second;
      magnitude_[size_t(v) * 3 + size_t(a)] = uint8_t(std::min<int64_t>(r < 0 ? -r : r, 255));
    }
  }
  round->prev = chosen_[k];
  if (best.place < allowed_.size()) {
    std::vector<size_t>& by_wins = round->by_wins;
    size_t i = size_t(std::find(by_wins.begin(), by_wins.end(), best.place) - by_wins.begin());
    ++round->wins[best.place];
    for (; i > 0 && round->wins[by_wins[i - 1]] < round->wins[by_wins[i]]; --i) std::swap(by_wins[i - 1], by_wins[i]);
  }
  std::vector<Triple>& paid = round->paid[b];
  if (std::find(paid.begin(), paid.end(), round->prev) == paid.end()) {
    bool motion = false;
    for (int a = 0; a < 3; ++a)
      if (pool_[round->prev[size_t(a)]].kind == PredictorKind::Motion) {
        motion = true;
        round->prev_row[a] = map_for(b, pool_[round->prev[size_t(a)]].r0).map.row[a];
      }
    if (motion) paid.push_back(round->prev);
  }
  round->res.insert(round->res.end(), best.res.begin(), best.res.end());
}

// One greedy pass over the clusters in decoding order, from the frame's original values.
void ClusterPlanner::run_round(int round_index) {
  std::copy(orig_.begin(), orig_.end(), qf_);
  Round round;
  round.wins.assign(allowed_.size(), 0);
  round.by_wins.resize(allowed_.size());
  for (size_t i = 0; i < round.by_wins.size(); ++i) round.by_wins[i] = i;
  round.paid.resize(blocks_);
  for (uint32_t k = 0; k < clusters_; ++k) choose_cluster(k, round_index, &round);
  frame_res_.swap(round.res);
}

// Makes allowed_ the choices used, most used first; false when they are more than a frame
// may keep (then the max_candidates most used ones stay, for a second round).
bool ClusterPlanner::restrict_to_most_used() {
  std::vector<std::pair<Triple, uint32_t>> uses;
  for (const Triple& t : chosen_) {
    auto it = std::find_if(uses.begin(), uses.end(), [&](const auto& u) { return u.first == t; });
    if (it == uses.end()) uses.emplace_back(t, 1);
    else ++it->second;
  }
  std::stable_sort(uses.begin(), uses.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  allowed_.clear();
  for (const auto& u : uses) allowed_.push_back(u.first);
  if (allowed_.size() <= max_candidates_) return true;
  allowed_.resize(max_candidates_);
  return false;
}

// The frame's candidates (the choices used, most used first), each cluster's index among
// them, and the motion maps of the blocks.
void ClusterPlanner::record_frame(uint32_t f) {
  const std::vector<Triple>& used = allowed_;
  FramePredictors& fp = plan_.frames[f];
  bool any_motion = false;
  for (const Triple& t : used) {
    fp.candidates.push_back({pool_[t[0]], pool_[t[1]], pool_[t[2]]});
    for (uint32_t c : t) any_motion = any_motion || pool_[c].kind == PredictorKind::Motion;
  }
  auto index_of = [&](const Triple& t) { return size_t(std::find(used.begin(), used.end(), t) - used.begin()); };
  if (used.size() > 1)
    for (const Triple& t : chosen_) fp.cluster_candidate.push_back(uint8_t(index_of(t)));
  if (!any_motion) return;
  fp.transforms.assign(size_t(blocks_) * used.size(), MotionTransform());
  for (uint32_t k = 0; k < clusters_; ++k)
    for (int a = 0; a < 3; ++a) {
      const PredictorChoice& c = pool_[chosen_[k][size_t(a)]];
      if (c.kind == PredictorKind::Motion)
        fp.transforms[size_t(k / M_) * used.size() + index_of(chosen_[k])].row[a] = map_for(k / M_, c.r0).map.row[a];
    }
}

void ClusterPlanner::plan_frame(uint32_t f) {
  qf_ = q_->data() + size_t(f) * stride_;
  input_ = frames_[f].data();
  runs_ = po_.snap ? &frame_axis_runs(po_, model_.residual, input_, V_, radius_, f, &scratch_runs_) : &scratch_runs_;
  std::copy(qf_, qf_ + stride_, orig_.begin());
  build_pool(f);
  fill_bases(f);
  maps_.assign(blocks_, {});
  // A choice is a pool entry per axis; at first each entry on all three axes.
  allowed_.clear();
  for (uint32_t c = 0; c < pool_.size(); ++c) allowed_.push_back({c, c, c});
  chosen_.assign(clusters_, Triple{});
  // The second round never uses more than max_candidates, so it always ends the loop.
  for (int round = 0; round < 2; ++round) {
    run_round(round);
    if (restrict_to_most_used()) break;
  }
  record_frame(f);
  for (const auto& [ctx, r] : frame_res_) table_.add(ctx, r);
  table_.next_frame();
  decoded_[f] = 1;
}

}  // namespace

PredictorPlan choose_cluster_plan(const Model& model, const std::vector<std::vector<float>>& frames, double radius,
                                  const std::vector<uint32_t>& order, uint32_t cluster_size, uint32_t motion_block,
                                  uint32_t max_candidates, std::vector<int32_t>* q, const ResidualOptions& options,
                                  const ResidualPlanOptions& po) {
  ClusterPlanner planner(model, frames, radius, cluster_size, motion_block, max_candidates, q, options, po);
  for (uint32_t f : order) {
    planner.plan_frame(f);
    if (po.meter) po.meter->add(1);
  }
  PredictorPlan plan = planner.take_plan();
  plan.order = order;
  return plan;
}

}  // namespace dcurve
