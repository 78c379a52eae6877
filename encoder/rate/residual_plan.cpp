#include "encoder/rate/residual_plan.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>

namespace dcurve {
namespace {

constexpr int kClasses = 2 * 41 + 1;

// Estimated bits of a residual when choosing among admissible grid points: what an
// adaptive exponent coder roughly pays.
int residual_cost(int64_t r) {
  if (r == 0) return 0;
  uint64_t m = r < 0 ? uint64_t(-r) : uint64_t(r);
  int e = 0;
  while (m >>= 1) ++e;
  return 2 + 2 * e;
}

double distance2(const ResidualLayer& layer, const float* x, const int64_t* k) {
  double d2 = 0;
  for (int a = 0; a < 3; ++a) {
    const double d = double(grid_to_model(layer, a, k[a])) - double(x[a]);
    d2 += d * d;
  }
  return d2;
}

// Moves qv (the vertex's three grid values) to the admissible grid point (decoded within
// sqrt(r2) of x) that is cheapest against `pred`, ties to the nearest; keeps qv when no
// other point qualifies.
void snap_vertex(const ResidualLayer& layer, const float* x, double radius, const int64_t* pred, int32_t* qv) {
  const double r2 = radius * radius;
  if (distance2(layer, x, pred) <= r2) {
    for (int a = 0; a < 3; ++a) qv[a] = int32_t(pred[a]);  // admissible, so within int32 range
    return;
  }
  int64_t lo[3], hi[3], k[3], best[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = int64_t(std::floor((double(x[a]) - radius - layer.origin[a]) / layer.step));
    hi[a] = int64_t(std::ceil((double(x[a]) + radius - layer.origin[a]) / layer.step));
    best[a] = qv[a];
  }
  int best_cost = 0;
  for (int a = 0; a < 3; ++a) best_cost += residual_cost(best[a] - pred[a]);
  double best_d2 = distance2(layer, x, best);
  for (k[0] = lo[0]; k[0] <= hi[0]; ++k[0])
    for (k[1] = lo[1]; k[1] <= hi[1]; ++k[1])
      for (k[2] = lo[2]; k[2] <= hi[2]; ++k[2]) {
        const double d2 = distance2(layer, x, k);
        if (d2 > r2) continue;
        const int cost = residual_cost(k[0] - pred[0]) + residual_cost(k[1] - pred[1]) + residual_cost(k[2] - pred[2]);
        if (cost < best_cost || (cost == best_cost && d2 < best_d2)) {
          best_cost = cost;
          best_d2 = d2;
          std::copy(k, k + 3, best);
        }
      }
  for (int a = 0; a < 3; ++a)
    if (best[a] >= INT32_MIN && best[a] <= INT32_MAX) qv[a] = int32_t(best[a]);
}

// Past frames most similar to frame f (sum of absolute grid differences on a sample of
// values), beyond the two nearest, which are always tried.
std::vector<uint32_t> reference_candidates(const std::vector<int32_t>& q, uint32_t V, uint32_t f,
                                           const ResidualPlanOptions& po) {
  std::vector<uint32_t> refs;
  for (uint32_t d = 1; d <= std::min<uint32_t>(f, 2); ++d) refs.push_back(d);
  const size_t stride = size_t(V) * 3, sample = std::max<size_t>(1, stride / 4096);
  std::vector<std::pair<uint64_t, uint32_t>> scored;
  for (uint32_t d = 3; d <= std::min(f, po.max_reference_distance); ++d) {
    const int32_t* a = q.data() + size_t(f) * stride;
    const int32_t* b = q.data() + size_t(f - d) * stride;
    uint64_t sum = 0;
    for (size_t i = 0; i < stride; i += sample) sum += uint64_t(std::llabs(int64_t(a[i]) - b[i]));
    scored.emplace_back(sum, d);
  }
  const size_t keep = std::min<size_t>(po.extra_references, scored.size());
  std::partial_sort(scored.begin(), scored.begin() + std::ptrdiff_t(keep), scored.end());
  for (size_t k = 0; k < keep; ++k) refs.push_back(scored[k].second);
  return refs;
}

}  // namespace

double estimate_residual_bits(const std::vector<int64_t>& residuals) {
  std::vector<uint64_t> hist(kClasses, 0);
  double mantissa = 0;
  for (int64_t r : residuals) {
    if (r == 0) { ++hist[0]; continue; }
    uint64_t m = r < 0 ? uint64_t(-r) : uint64_t(r);
    int e = 0;
    while (m >>= 1) ++e;
    e = std::min(e, 40);
    mantissa += e;
    ++hist[size_t(1 + 2 * e + (r < 0))];
  }
  const double n = double(residuals.size());
  double bits = mantissa;
  for (uint64_t h : hist)
    if (h) bits -= double(h) * std::log2(double(h) / n);
  return bits;
}

PredictorPlan choose_plan_and_grid(const Model& model, const std::vector<std::vector<float>>& frames,
                                   double max_distance, std::vector<int32_t>* q, const ResidualOptions& options,
                                   const ResidualPlanOptions& po) {
  const uint32_t V = model.meta.vertex_count, F = model.meta.frame_count;
  const size_t stride = size_t(V) * 3;
  const Traversal trav = build_traversal(model);
  // A hair inside the bound, so rounding in the error measurement cannot push it over.
  const double radius = max_distance * (1.0 - 1e-9);
  PredictorPlan plan(size_t(F) * 3);
  std::vector<int64_t> base(stride), residuals(stride);
  std::vector<int32_t> scratch(stride), best_frame(stride);
  for (uint32_t f = 0; f < F; ++f) {
    std::vector<PredictorChoice> candidates;
    auto add = [&](PredictorKind kind, uint32_t d) {
      if (!(po.kinds >> int(kind) & 1)) return;
      for (SpatialMode s : {SpatialMode::Off, SpatialMode::Mean, SpatialMode::Parallelogram})
        if (po.spatial_modes >> int(s) & 1) candidates.push_back({kind, d, s});
    };
    add(PredictorKind::None, 1);  // after a cut, a frame may be best predicted from itself alone
    for (uint32_t d : reference_candidates(*q, V, f, po)) add(PredictorKind::Reference, d);
    if (f >= 2) add(PredictorKind::SecondOrder, 1);
    if (options.model_prediction) add(PredictorKind::Model, 1);
    if (candidates.empty())
      candidates.push_back({f == 0 ? PredictorKind::None : PredictorKind::Reference, 1, SpatialMode::Off});
    int32_t* qf = q->data() + size_t(f) * stride;
    double best = HUGE_VAL;
    for (const PredictorChoice& c : candidates) {
      const PredictorChoice choice[3] = {c, c, c};
      for (int a = 0; a < 3; ++a) base_prediction(c, f, a, V, q->data(), options, &base[size_t(a) * V]);
      std::copy(qf, qf + stride, scratch.begin());
      for (uint32_t pos = 0; pos < V; ++pos) {
        const uint32_t v = trav.order[pos];
        int64_t pred[3];
        vertex_prediction(choice, trav, pos, V, scratch.data(), base.data(), pred);
        int32_t* qv = &scratch[size_t(v) * 3];
        if (po.snap) snap_vertex(model.residual, &frames[f][size_t(v) * 3], radius, pred, qv);
        for (int a = 0; a < 3; ++a) residuals[size_t(pos) * 3 + size_t(a)] = int64_t(qv[a]) - pred[a];
      }
      const double bits = estimate_residual_bits(residuals);
      if (bits < best) {
        best = bits;
        best_frame.swap(scratch);
        for (int a = 0; a < 3; ++a) plan[size_t(f) * 3 + size_t(a)] = c;
      }
    }
    std::copy(best_frame.begin(), best_frame.end(), qf);
  }
  return plan;
}

}  // namespace dcurve
