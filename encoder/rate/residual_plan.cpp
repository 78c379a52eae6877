#include "encoder/rate/residual_plan.h"

#include "codec/common/int_coder.h"
#include "codec/compress/residual_encoder.h"
#include "encoder/parallel.h"
#include "encoder/rate/cluster_plan.h"
#include "encoder/rate/plan_steps.h"
#include "encoder/work_meter.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <vector>

namespace dcurve {

// Estimated bits of a residual when choosing among admissible grid points: what an
// adaptive exponent coder roughly pays.
int residual_cost(int64_t r) { return r == 0 ? 0 : 2 + 2 * floor_log2(magnitude_of(r)); }

int residual_class(int64_t r, int* exponent) {
  *exponent = 0;
  if (r == 0) return 0;
  *exponent = std::min(floor_log2(magnitude_of(r)), kMaxExponent);
  return 1 + 2 * *exponent + (r < 0);
}

// Signed distance from x to grid value k's decoded coordinate on axis a: non-decreasing in k,
// since the decoder's conversion (grid_to_model) is monotonic.
static double offset(const ResidualLayer& layer, int a, double xa, int64_t k) {
  return double(grid_to_model(layer, a, k)) - xa;
}

static double distance2(const ResidualLayer& layer, const float* x, const int64_t* k) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = offset(layer, a, x[a], k[a]);
    d2 += d * d;
  }
  return d2;
}

static AxisRun axis_run(const ResidualLayer& layer, int a, float x, double radius) {
  const double r2 = radius * radius, xa = x;
  auto d2_of = [&](int64_t k) {
    const double d = offset(layer, a, xa, k);
    return d * d;
  };
  // The admissible values form one run [lo, hi]: the decoded position is monotonic in k.
  AxisRun run;
  run.lo = int64_t(std::floor((xa - radius - layer.origin[a]) / layer.step));
  run.hi = int64_t(std::ceil((xa + radius - layer.origin[a]) / layer.step));
  while (run.lo <= run.hi && d2_of(run.lo) > r2) ++run.lo;
  while (run.hi >= run.lo && d2_of(run.hi) > r2) --run.hi;
  if (run.lo > run.hi) return run;
  // The lowest of the values nearest x: the first whose offset is >= 0, or the first of the
  // (float-rounded, so possibly repeated) offsets just below 0 when those are as near.
  auto first_at_least = [&](int64_t l, int64_t h, double v) {
    while (l <= h) {
      const int64_t mid = l + (h - l) / 2;
      if (offset(layer, a, xa, mid) >= v) h = mid - 1;
      else l = mid + 1;
    }
    return l;
  };
  const int64_t above = first_at_least(run.lo, run.hi, 0.0);
  run.nearest = above;
  if (above > run.lo) {
    const double below = offset(layer, a, xa, above - 1);
    if (above > run.hi || below * below <= d2_of(above)) run.nearest = first_at_least(run.lo, above - 1, below);
  }
  return run;
}

std::vector<AxisRun> axis_runs(const ResidualLayer& layer, const float* xyz, size_t V, double radius) {
  std::vector<AxisRun> runs(V * 3);
  for (size_t i = 0; i < runs.size(); ++i) runs[i] = axis_run(layer, int(i % 3), xyz[i], radius);
  return runs;
}

const std::vector<AxisRun>& frame_axis_runs(const ResidualPlanOptions& po, const ResidualLayer& layer,
                                            const float* xyz, size_t V, double radius, uint32_t f,
                                            std::vector<AxisRun>* scratch) {
  if (po.axis_runs) return (*po.axis_runs)[f];
  *scratch = axis_runs(layer, xyz, V, radius);
  return *scratch;
}

void snap_vertex(const ResidualLayer& layer, const float* x, double radius, double distance_weight,
                 const int64_t* pred, int32_t* qv) {
  const AxisRun runs[3] = {axis_run(layer, 0, x[0], radius), axis_run(layer, 1, x[1], radius),
                           axis_run(layer, 2, x[2], radius)};
  snap_vertex(layer, x, runs, radius, distance_weight, pred, qv);
}

// Moves qv (the vertex's three grid values) to the admissible grid point (decoded within
// radius of x) with the lowest score: estimated bits against `pred`, plus
// distance_weight * (distance / radius)^2 bits, since a point near the input predicts
// later frames better; keeps qv when no other point qualifies.
void snap_vertex(const ResidualLayer& layer, const float* x, const AxisRun* runs, double radius,
                 double distance_weight, const int64_t* pred, int32_t* qv) {
  const double r2 = radius * radius;
  auto score = [&](const int64_t* k, double d2) {
    return residual_cost(k[0] - pred[0]) + residual_cost(k[1] - pred[1]) + residual_cost(k[2] - pred[2]) +
           distance_weight * d2 / r2;
  };
  // Any nonzero residual costs at least 2: below that weight an admissible prediction wins.
  if (distance_weight < 2 && distance2(layer, x, pred) <= r2) {
    for (int a = 0; a < 3; ++a) qv[a] = int32_t(pred[a]);  // admissible, so within int32 range
    return;
  }
  // The score separates by axis, and on each axis the bits depend only on the band of
  // |value - prediction| (0, 1, 2..3, 4..7, ...). Within a band the value nearest the
  // input scores best (same bits, less distance) and keeps every other axis admissible, so
  // only one value per axis and band can win: a few per axis, instead of every lattice
  // point of the ball, whose count grows with the cube of the grid refinement. Fewer still:
  // a value costing more bits than another of the axis and no nearer the input never wins
  // (swapping it for the other keeps the point admissible and lowers the score), so only
  // the bands from the prediction towards the nearest value count, each kept only when
  // nearer than every cheaper one.
  struct Option {
    int bits;
    double d2;
    int64_t k;
  };
  // At most one option for "equal to pred" and one per exponent band.
  std::array<Option, 64> options[3];
  size_t count[3] = {0, 0, 0};
  int64_t best[3];
  for (int a = 0; a < 3; ++a) {
    const double xa = x[a];
    auto d2_of = [&](int64_t k) {
      const double d = offset(layer, a, xa, k);
      return d * d;
    };
    const int64_t lo = runs[a].lo, hi = runs[a].hi, nearest = runs[a].nearest;
    best[a] = qv[a];
    if (lo > hi) continue;
    // The value of [l, h] (within the run) nearest the input, the lowest of equally near
    // ones: |offset| does not rise up to `nearest` and does not fall after it.
    auto nearest_in = [&](int64_t l, int64_t h) {
      if (nearest < l) return l;
      if (nearest <= h) return nearest;
      const double dh = offset(layer, a, xa, h);
      while (h > l && offset(layer, a, xa, h - 1) >= dh) --h;
      return h;
    };
    const int64_t p = pred[a];
    Option* o = options[a].data();
    double nearer_than = HUGE_VAL;
    if (lo <= p && p <= hi) {
      nearer_than = d2_of(p);
      o[count[a]++] = {0, nearer_than, p};
    }
    if (p == nearest) continue;
    // Band e: |k - p| in [2^e, 2^(e+1) - 1], all costing residual_cost = 2 + 2e, on the
    // side of the nearest value, up to the band holding it. Unsigned: p may lie far
    // outside the run.
    const bool up = nearest > p;
    const uint64_t reach = up ? uint64_t(nearest) - uint64_t(p) : uint64_t(p) - uint64_t(nearest);
    for (int e = 0; e < 63 && (uint64_t(1) << e) <= reach; ++e) {
      const uint64_t m1 = uint64_t(1) << e, m2 = (uint64_t(2) << e) - 1;
      int64_t l, h;
      if (up) {
        l = std::max(lo, int64_t(uint64_t(p) + m1));
        h = uint64_t(hi) - uint64_t(p) <= m2 ? hi : int64_t(uint64_t(p) + m2);
      } else {
        h = std::min(hi, int64_t(uint64_t(p) - m1));
        l = uint64_t(p) - uint64_t(lo) <= m2 ? lo : int64_t(uint64_t(p) - m2);
      }
      if (l > h) continue;
      const int64_t k = nearest_in(l, h);
      const double d2 = d2_of(k);
      if (d2 < nearer_than) {
        nearer_than = d2;
        o[count[a]++] = {2 + 2 * e, d2, k};
      }
    }
  }
  double best_d2 = distance2(layer, x, best), best_score = score(best, best_d2);
  // Options come cheapest first, and scores only grow with bits (distance_weight >= 0):
  // once a prefix is dearer than the best point the rest of that list cannot win.
  for (size_t i = 0; i < count[0]; ++i) {
    const Option& ox = options[0][i];
    if (ox.bits > best_score) break;
    for (size_t j = 0; j < count[1]; ++j) {
      const Option& oy = options[1][j];
      if (ox.bits + oy.bits > best_score) break;
      const double dxy = ox.d2 + oy.d2;
      if (dxy > r2) continue;
      for (size_t k = 0; k < count[2]; ++k) {
        const Option& oz = options[2][k];
        const int bits = ox.bits + oy.bits + oz.bits;
        if (bits > best_score) break;
        const double d2 = dxy + oz.d2;
        if (d2 > r2) continue;
        const double sc = bits + distance_weight * d2 / r2;
        // Among equally cheap points the one nearest the input: it leaves the most room
        // before later predictions leave the ball (the first found would drift to a corner).
        if (sc < best_score || (sc == best_score && d2 < best_d2)) {
          best_score = sc;
          best_d2 = d2;
          best[0] = ox.k;
          best[1] = oy.k;
          best[2] = oz.k;
        }
      }
    }
  }
  for (int a = 0; a < 3; ++a)
    if (best[a] >= INT32_MIN && best[a] <= INT32_MAX) qv[a] = int32_t(best[a]);
}

// Classes of the earlier neighbours' residual magnitudes, per axis (0..3, 4 for none): let
// the estimate see that clustered residuals are cheaper to code than scattered ones.
void neighbour_classes(const Traversal& t, uint32_t pos, const std::vector<uint8_t>& magnitude, int classes[3]) {
  const uint32_t begin = t.nb_offsets[pos], end = t.nb_offsets[pos + 1];
  if (begin == end) {
    classes[0] = classes[1] = classes[2] = 4;
    return;
  }
  uint32_t sum[3] = {0, 0, 0};
  for (uint32_t k = begin; k < end; ++k) {
    const uint8_t* m = &magnitude[size_t(t.nb[k]) * 3];
    sum[0] += m[0];
    sum[1] += m[1];
    sum[2] += m[2];
  }
  for (int a = 0; a < 3; ++a) classes[a] = int(std::min<uint32_t>((sum[a] + (end - begin) - 1) / (end - begin), 3));
}

// Decoded frames most similar to frame f (sum of absolute grid differences on a sample
// of values), other than the ones always tried.
static std::vector<uint32_t> similar_frames(const std::vector<int32_t>& q, uint32_t V, uint32_t f,
                                     const std::vector<uint8_t>& decoded, const std::vector<uint32_t>& tried,
                                     const ResidualPlanOptions& po) {
  const size_t stride = size_t(V) * 3, sample = std::max<size_t>(1, stride / 4096);
  std::vector<std::pair<uint64_t, uint32_t>> scored;
  for (uint32_t r = 0; r < decoded.size(); ++r) {
    if (!decoded[r] || std::find(tried.begin(), tried.end(), r) != tried.end()) continue;
    if ((r > f ? r - f : f - r) > po.max_reference_distance) continue;
    const int32_t* a = q.data() + size_t(f) * stride;
    const int32_t* b = q.data() + size_t(r) * stride;
    uint64_t sum = 0;
    for (size_t i = 0; i < stride; i += sample) sum += uint64_t(std::llabs(int64_t(a[i]) - b[i]));
    scored.emplace_back(sum, r);
  }
  const size_t keep = std::min<size_t>(po.extra_references, scored.size());
  std::partial_sort(scored.begin(), scored.begin() + std::ptrdiff_t(keep), scored.end());
  std::vector<uint32_t> out;
  for (size_t k = 0; k < keep; ++k) out.push_back(scored[k].second);
  return out;
}

// Time order when gop is 1; otherwise every gop-th frame (and the last) in time order,
// each followed by the frames before it down to the previous key, coded by recursive
// midpoints so that each is interpolated between two decoded frames.
static std::vector<uint32_t> coding_order(uint32_t F, uint32_t gop) {
  std::vector<uint32_t> order;
  if (F == 0) return order;
  order.push_back(0);
  struct Range { uint32_t lo, hi; };
  for (uint32_t key = 0; key + 1 < F;) {
    const uint32_t next = std::min(F - 1, key + std::max(gop, 1u));
    order.push_back(next);
    std::vector<Range> stack{{key, next}};
    while (!stack.empty()) {
      const Range r = stack.back();
      stack.pop_back();
      if (r.hi - r.lo < 2) continue;
      const uint32_t mid = r.lo + (r.hi - r.lo) / 2;
      order.push_back(mid);
      stack.push_back({mid, r.hi});
      stack.push_back({r.lo, mid});
    }
    key = next;
  }
  return order;
}

// Candidates for frame f given the decoded frames: self (None), nearest decoded frames on
// each side, interpolation between them, extrapolation from the two nearest before, the
// most similar decoded poses, the model; each with every allowed spatial mode.
std::vector<PredictorChoice> candidates_for(const std::vector<int32_t>& q, uint32_t V, uint32_t f,
                                            const std::vector<uint8_t>& decoded, const ResidualOptions& options,
                                            const ResidualPlanOptions& po) {
  const uint32_t F = uint32_t(decoded.size()), none = UINT32_MAX;
  uint32_t below = none, below2 = none, above = none;
  for (uint32_t r = f; r-- > 0;)
    if (decoded[r]) {
      if (below == none) below = r;
      else { below2 = r; break; }
    }
  for (uint32_t r = f + 1; r < F; ++r)
    if (decoded[r]) { above = r; break; }
  std::vector<PredictorChoice> out;
  auto add = [&](PredictorKind kind, uint32_t r0, uint32_t r1) {
    if (!(po.kinds >> int(kind) & 1)) return;
    for (uint8_t m = 0; m < kSpatialModeCount; ++m) {
      const SpatialMode s = SpatialMode(m);
      // Geometric and Fit weights come from the chunk's first frame (decoded first), or with
      // po.geometry_per_frame from the reference pose or the nearest decoded frame.
      const uint32_t g = !po.geometry_per_frame && decoded[0] ? 0
                         : has_reference(kind)                ? r0
                         : below != none                      ? below
                                                              : above;
      const PredictorChoice c{kind, r0, r1, s, uses_geometry(s) ? g : 0};
      if (po.spatial_modes >> int(s) & 1 && predictor_usable(c, f, decoded, options)) out.push_back(c);
    }
  };
  add(PredictorKind::None, 0, 0);
  std::vector<uint32_t> tried;
  for (uint32_t r : {below, above})
    if (r != none) {
      add(PredictorKind::Reference, r, 0);
      tried.push_back(r);
    }
  if (below != none && above != none) add(PredictorKind::Linear, below, above);
  if (below != none && below2 != none) add(PredictorKind::Linear, below, below2);
  for (uint32_t r : similar_frames(q, V, f, decoded, tried, po)) add(PredictorKind::Reference, r, 0);
  if (options.model_prediction) add(PredictorKind::Model, 0, 0);
  if (out.empty()) out.push_back({PredictorKind::None, 0, 0, SpatialMode::Off});
  return out;
}

// mantissa bits plus, per context, the order-0 entropy of its exponent classes: hist holds
// kResidualClasses counts per context. One summation order, so equal histograms give
// equal figures bit for bit (the plan breaks ties by candidate order).
static double histogram_bits(const uint64_t* hist, const uint64_t* count, size_t contexts, double mantissa) {
  double bits = mantissa;
  for (size_t c = 0; c < contexts; ++c)
    for (size_t k = 0; k < size_t(kResidualClasses); ++k) {
      const uint64_t h = hist[c * kResidualClasses + k];
      if (h) bits -= double(h) * std::log2(double(h) / double(count[c]));
    }
  return bits;
}

RunningBits::RunningBits(size_t max_count) : step_(max_count + 1) {
  auto xlog2x = [](double x) { return x > 0 ? x * std::log2(x) : 0.0; };
  for (size_t x = 0; x <= max_count; ++x) step_[x] = xlog2x(double(x) + 1) - xlog2x(double(x));
}

void RunningBits::reset() {
  std::fill(hist_.begin(), hist_.end(), 0u);
  std::fill(count_.begin(), count_.end(), 0u);
  bits_ = mantissa_ = 0;
}

// Adding r to a context of n values, h of them in r's class, changes n log2 n - sum h log2 h
// by d(n) - d(h), d(x) = (x + 1) log2(x + 1) - x log2 x: never negative, as d increases and
// h <= n. So the running figure never shrinks.
void RunningBits::add(size_t context, int64_t r) {
  int e;
  uint64_t& h = hist_[context * kResidualClasses + size_t(residual_class(r, &e))];
  uint64_t& n = count_[context];
  bits_ += e + step_[n] - step_[h];
  mantissa_ += e;
  ++h;
  ++n;
}

double RunningBits::estimate() const { return histogram_bits(hist_.data(), count_.data(), kContexts, mantissa_); }

double estimate_residual_bits(const std::vector<int64_t>& residuals, const std::vector<uint8_t>& contexts) {
  size_t used = 0;
  for (uint8_t c : contexts) used = std::max(used, size_t(c) + 1);
  std::vector<uint64_t> hist(used * kResidualClasses, 0), count(used, 0);
  double mantissa = 0;
  for (size_t i = 0; i < residuals.size(); ++i) {
    const size_t c = contexts[i];
    ++count[c];
    int e;
    ++hist[c * kResidualClasses + size_t(residual_class(residuals[i], &e))];
    mantissa += e;
  }
  return histogram_bits(hist.data(), count.data(), used, mantissa);
}

namespace {

// The snapping radius of a plan for max_distance: a hair inside the bound, so rounding in
// the error measurement cannot push it over.
double plan_radius(double max_distance) { return max_distance * (1.0 - 1e-9); }

// Chooses predictors and grid values for one coding order; returns the estimated bits.
double plan_for_order(const Model& model, const Traversal& trav, const std::vector<std::vector<float>>& frames,
                      double radius, const std::vector<uint32_t>& order, const ResidualOptions& options,
                      const ResidualPlanOptions& po, std::vector<int32_t>* q, PredictorPlan* plan) {
  const uint32_t V = model.meta.vertex_count, F = model.meta.frame_count;
  const size_t stride = size_t(V) * 3;
  std::vector<PredictorChoice> choices(size_t(F) * 3);
  std::vector<uint8_t> decoded(F, 0);
  std::vector<int64_t> base(stride);
  std::vector<uint8_t> magnitude(stride);  // by vertex, clamped
  std::vector<int32_t> scratch(stride), best_frame(stride);
  double total = 0;
  SpatialWeightsCache geometry(options.weights_source);
  std::vector<AxisRun> scratch_runs;
  RunningBits running(stride);
  PredictorChoice last_winner{PredictorKind::None, 0, 0, SpatialMode::Off};
  for (uint32_t f : order) {
    int32_t* qf = q->data() + size_t(f) * stride;
    double best = HUGE_VAL;
    size_t best_index = SIZE_MAX;
    const std::vector<AxisRun>& runs =
        po.snap ? frame_axis_runs(po, model.residual, frames[f].data(), V, radius, f, &scratch_runs) : scratch_runs;
    const std::vector<PredictorChoice> candidates = candidates_for(*q, V, f, decoded, options, po);
    // The previous frame's kind and spatial mode usually win again: tried first, they give
    // the bound that drops the others early. Ties still go to the earliest in the list.
    size_t first = 0;
    while (first < candidates.size() &&
           !(candidates[first].kind == last_winner.kind && candidates[first].spatial == last_winner.spatial))
      ++first;
    if (first == candidates.size()) first = 0;
    for (size_t n = 0; n < candidates.size(); ++n) {
      const size_t index = n == 0 ? first : n <= first ? n - 1 : n;
      const PredictorChoice& c = candidates[index];
      const PredictorChoice choice[3] = {c, c, c};
      const int32_t* weights[3];
      geometry.for_choice(trav, q->data(), choice, weights);
      for (int a = 0; a < 3; ++a) base_prediction(c, f, a, V, q->data(), options, &base[size_t(a) * V]);
      std::copy(qf, qf + stride, scratch.begin());
      // Margin for the running sum's rounding against estimate_residual_bits' own.
      const double limit = best + 1e-9 * best + 1e-6;
      running.reset();
      bool dropped = false;
      for (uint32_t pos = 0; pos < V && !dropped; ++pos) {
        const uint32_t v = trav.order[pos];
        int64_t pred[3];
        vertex_prediction(choice, trav, pos, scratch.data(),
                          [&](uint32_t u, int a) { return base[size_t(a) * V + u]; }, pred, weights);
        int32_t* qv = &scratch[size_t(v) * 3];
        if (po.snap)
          snap_vertex(model.residual, &frames[f][size_t(v) * 3], &runs[size_t(v) * 3], radius, po.distance_weight, pred,
                      qv);
        uint8_t axis_max = 0;
        int classes[3];
        neighbour_classes(trav, pos, magnitude, classes);
        for (int a = 0; a < 3; ++a) {
          const int64_t r = int64_t(qv[a]) - pred[a];
          running.add(size_t(classes[a]) * 3 + std::min<uint8_t>(axis_max, 2), r);
          magnitude[size_t(v) * 3 + size_t(a)] = uint8_t(std::min<int64_t>(r < 0 ? -r : r, 255));
          axis_max = std::max(axis_max, magnitude[size_t(v) * 3 + size_t(a)]);
        }
        dropped = running.bits() > limit;
      }
      if (dropped) continue;
      const double bits = running.estimate();
      if (bits < best || (bits == best && index < best_index)) {
        best = bits;
        best_index = index;
        last_winner = c;
        best_frame.swap(scratch);
        for (int a = 0; a < 3; ++a) choices[size_t(f) * 3 + size_t(a)] = c;
      }
    }
    std::copy(best_frame.begin(), best_frame.end(), qf);
    decoded[f] = 1;
    total += best;
    if (po.meter) po.meter->add(1);
  }
  *plan = uniform_plan(order, choices);
  return total;
}

}  // namespace

std::vector<std::vector<AxisRun>> plan_axis_runs(const Model& model, const std::vector<std::vector<float>>& frames,
                                                 double max_distance, int threads) {
  std::vector<std::vector<AxisRun>> runs(frames.size());
  parallel_for(frames.size(), threads, [&](size_t f) {
    runs[f] = axis_runs(model.residual, frames[f].data(), model.meta.vertex_count, plan_radius(max_distance));
  });
  return runs;
}

ResidualPlanOptions narrow_to_plan(const ResidualPlanOptions& po, const PredictorPlan& won) {
  ResidualPlanOptions narrow = po;
  const uint32_t F = uint32_t(won.order.size());
  for (uint32_t gop : po.gop_sizes)
    if (coding_order(F, gop) == won.order) {
      narrow.gop_sizes = {gop};
      break;
    }
  narrow.cluster_layouts.clear();
  for (const ResidualPlanOptions::ClusterLayout& layout : po.cluster_layouts)
    if (layout.cluster_size == won.cluster_size && layout.motion_block == won.motion_block) {
      narrow.cluster_layouts = {layout};
      break;
    }
  narrow.geometry_per_frame = po.geometry_per_frame || geometry_per_frame(won);
  narrow.try_geometry_per_frame = false;
  return narrow;
}

namespace {
// A plan, the grid values it chose and its coded size.
struct PlanTrial {
  std::vector<int32_t> q;
  PredictorPlan plan;
  size_t bytes = SIZE_MAX;
};

// Runs run(i) for the coding orders (*orders, by ascending group size) likely to code
// smallest. A clip's sizes mostly fall or rise steadily along the list (time order wins
// short chunks, the largest group long smooth clips), so both ends are planned, then the
// orders from the smaller end inwards while each codes smaller than the one before: two
// or three plans of the five on most inputs. An order left out keeps bytes SIZE_MAX.
void walk_orders(const std::vector<PlanTrial>& orders, int threads, const std::function<void(size_t)>& run) {
  const size_t n = orders.size(), last = n - 1;
  const size_t ends[2] = {0, last};
  parallel_for(n > 1 ? 2 : 1, threads, [&](size_t k) { run(ends[k]); });
  if (n < 3) return;
  const bool from_first = orders[0].bytes <= orders[last].bytes;
  for (size_t at = from_first ? 0 : last;;) {
    const size_t next = from_first ? at + 1 : at - 1;
    if (next == (from_first ? last : 0)) break;
    run(next);
    if (!(orders[next].bytes < orders[at].bytes)) break;
    at = next;
  }
}

// The smallest of po's coding orders and cluster layouts, each planned from the values q.
// `options` names the traversal every trial reuses.
PlanTrial smallest_trial(const Model& model, const Traversal& trav, const std::vector<std::vector<float>>& frames,
                         double radius, const std::vector<int32_t>& q, const ResidualOptions& options,
                         const ResidualPlanOptions& po) {
  // Independent trials run in parallel; the first smallest wins, whatever the thread count.
  auto keep_smallest = [](std::vector<PlanTrial>& trials, PlanTrial* best) {
    for (PlanTrial& t : trials)
      if (t.bytes < best->bytes) *best = std::move(t);
  };
  std::vector<PlanTrial> orders(po.gop_sizes.size()), layouts(po.cluster_layouts.size());
  auto run_order = [&](size_t i) {
    PlanTrial& t = orders[i];
    t.q = q;
    plan_for_order(model, trav, frames, radius, coding_order(model.meta.frame_count, po.gop_sizes[i]), options, po,
                   &t.q, &t.plan);
    // The order is judged by the coded size: the estimate that ranks predictors within a
    // frame ignores the contexts, which favour some orders.
    t.bytes = encode_residuals(model, t.q, &t.plan, options).size();
  };
  // Per-cluster predictors on the winning order, kept when they code smaller.
  auto run_layout = [&](size_t i, const std::vector<uint32_t>& order) {
    PlanTrial& t = layouts[i];
    t.q = q;
    const ResidualPlanOptions::ClusterLayout& layout = po.cluster_layouts[i];
    ResidualPlanOptions layout_po = po;
    layout_po.extra_references = layout.extra_references;
    t.plan = choose_cluster_plan(model, frames, radius, order, layout.cluster_size, layout.motion_block,
                                 po.max_candidates, &t.q, options, layout_po);
    t.bytes = encode_residuals(model, t.q, &t.plan, options).size();
  };
  PlanTrial best;
  if (orders.size() == 1) {
    // One order wins before it is tried: the layouts need not wait for its plan, and all
    // run side by side (the low-rank screening plans this way, once per count and step).
    const std::vector<uint32_t> order = coding_order(model.meta.frame_count, po.gop_sizes[0]);
    parallel_for(layouts.size() + 1, po.threads, [&](size_t i) {
      if (i < layouts.size()) run_layout(i, order);
      else run_order(0);
    });
    keep_smallest(orders, &best);
  } else {
    walk_orders(orders, po.threads, run_order);
    keep_smallest(orders, &best);
    parallel_for(layouts.size(), po.threads, [&](size_t i) { run_layout(i, best.plan.order); });
  }
  keep_smallest(layouts, &best);
  return best;
}

// The distinct geometry frames `plan` names, up to `most` of them.
std::vector<uint32_t> geometry_frames(const PredictorPlan& plan, size_t most) {
  std::vector<uint32_t> out;
  for (const FramePredictors& fp : plan.frames)
    for (const auto& candidate : fp.candidates)
      for (const PredictorChoice& c : candidate) {
        if (!uses_geometry(c.spatial) || std::find(out.begin(), out.end(), c.g) != out.end()) continue;
        out.push_back(c.g);
        if (out.size() >= most) return out;
      }
  return out;
}
}  // namespace

bool geometry_per_frame(const PredictorPlan& plan) { return geometry_frames(plan, 2).size() > 1; }

PredictorPlan choose_plan_and_grid(const Model& model, const std::vector<std::vector<float>>& frames,
                                   double max_distance, std::vector<int32_t>* q, const ResidualOptions& caller_options,
                                   const ResidualPlanOptions& po) {
  Traversal owned;
  const Traversal& trav = traversal_for(model, caller_options, &owned);
  ResidualOptions options = caller_options;  // every trial below reuses this traversal
  options.traversal = &trav;
  const double radius = plan_radius(max_distance);
  PlanTrial best = smallest_trial(model, trav, frames, radius, *q, options, po);
  // A table per frame, on the order and layout that won: kept only where it pays.
  if (po.try_geometry_per_frame && !po.geometry_per_frame && !geometry_frames(best.plan, 1).empty()) {
    ResidualPlanOptions per_frame = narrow_to_plan(po, best.plan);
    per_frame.geometry_per_frame = true;
    PlanTrial tables = smallest_trial(model, trav, frames, radius, *q, options, per_frame);
    if (double(tables.bytes) < double(best.bytes) * (1 - kPerFrameGeometryGain)) best = std::move(tables);
  }
  q->swap(best.q);
  return best.plan;
}

}  // namespace dcurve

namespace dcurve {
namespace {
// The part of a whole-animation input that one chunk's plan sees: the chunk's frames, its
// grid values and Model predictions, its snapping runs.
struct ChunkInput {
  Model model;
  std::vector<std::vector<float>> frames;
  std::vector<int32_t> q, prediction;
  std::vector<std::vector<AxisRun>> runs;
};

void cut_chunk(const Model& model, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& q,
               const ResidualOptions& options, const ResidualPlanOptions& po, ChunkSpan span, ChunkInput* in) {
  const size_t stride = size_t(model.meta.vertex_count) * 3;
  auto cut = [&](const auto& all, size_t per_frame, auto* out) {
    out->assign(all.begin() + ptrdiff_t(per_frame * span.first),
                all.begin() + ptrdiff_t(per_frame * (span.first + span.count)));
  };
  in->model.meta.frame_count = span.count;
  cut(frames, 1, &in->frames);
  cut(q, stride, &in->q);
  if (options.model_prediction) cut(*options.model_prediction, stride, &in->prediction);
  if (po.axis_runs) cut(*po.axis_runs, 1, &in->runs);
}

// Plans one chunk on its own (its frames, values, predictions and snapping runs) and writes
// its grid values back into *q.
// `model` is the clip's model without its payload or low-rank model (what a chunk's plan
// needs of it, copied once per chunk).
void plan_chunk(const Model& model, const std::vector<std::vector<float>>& frames, double max_distance,
                const ResidualOptions& options, const ResidualPlanOptions& po, ChunkSpan span,
                std::vector<int32_t>* q, PredictorPlan* out) {
  ChunkInput in;
  in.model = model;
  cut_chunk(model, frames, *q, options, po, span, &in);
  ResidualOptions chunk_options = options;
  chunk_options.model_prediction = options.model_prediction ? &in.prediction : nullptr;
  ResidualPlanOptions chunk_po = po;
  chunk_po.axis_runs = po.axis_runs ? &in.runs : nullptr;
  *out = choose_plan_and_grid(in.model, in.frames, max_distance, &in.q, chunk_options, chunk_po);
  const size_t stride = size_t(model.meta.vertex_count) * 3;
  std::copy(in.q.begin(), in.q.end(), q->begin() + ptrdiff_t(stride * span.first));
}
}  // namespace

ResidualPlan choose_chunked_plan(const Model& model, const std::vector<std::vector<float>>& frames,
                                 double max_distance, std::vector<int32_t>* q, const ResidualOptions& options,
                                 const ResidualPlanOptions& po) {
  const uint32_t F = model.meta.frame_count;
  const uint32_t K = model.residual.chunk_frames == 0 ? F : std::min(model.residual.chunk_frames, F);
  ResidualPlan plan;
  plan.chunk_frames = std::max(K, 1u);
  if (K >= F) {
    plan.chunks.push_back(choose_plan_and_grid(model, frames, max_distance, q, options, po));
    return plan;
  }
  Traversal owned;
  ResidualOptions shared = options;
  shared.traversal = &traversal_for(model, options, &owned);
  const uint32_t chunks = chunk_count(F, K);
  plan.chunks.resize(chunks);
  Model lean = model;  // the basis and payload stay out of every chunk's copy
  lean.residual.payload.clear();
  lean.low_rank = LowRankModel();
  // Chunks are planned independently (format 3), side by side: each writes only its own
  // plan and frames, so the result does not depend on the thread count.
  parallel_for(chunks, po.threads, [&](size_t c) {
    plan_chunk(lean, frames, max_distance, shared, po, chunk_span(F, K, uint32_t(c)), q, &plan.chunks[c]);
  });
  return plan;
}

}  // namespace dcurve
