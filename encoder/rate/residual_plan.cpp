#include "encoder/rate/residual_plan.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdlib>

namespace dcurve {
namespace {

constexpr int kClasses = 2 * 41 + 1;

// Residuals of frame f, axis a under `c`, in traversal order (the decoder's order).
void residuals_of(const Model& model, const Traversal& trav, const std::vector<int32_t>& q,
                  const ResidualOptions& options, const PredictorChoice& c, uint32_t f, int a,
                  std::vector<int64_t>* base, std::vector<int64_t>* out) {
  const uint32_t V = model.meta.vertex_count;
  base_prediction(c, f, a, V, q.data(), options, base->data());
  const int32_t* qf = q.data() + size_t(f) * V * 3;
  out->resize(V);
  for (uint32_t pos = 0; pos < V; ++pos) {
    const uint32_t v = trav.order[pos];
    int64_t pred = (*base)[v];
    if (c.neighbours) pred += neighbour_correction(trav, pos, a, qf, base->data());
    (*out)[pos] = int64_t(qf[size_t(v) * 3 + size_t(a)]) - pred;
  }
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

PredictorPlan choose_predictor_plan(const Model& model, const std::vector<int32_t>& q,
                                    const ResidualOptions& options, const ResidualPlanOptions& po) {
  const uint32_t V = model.meta.vertex_count, F = model.meta.frame_count;
  const Traversal trav = build_traversal(model);
  PredictorPlan plan(size_t(F) * 3);
  std::vector<int64_t> base(V), res;
  for (uint32_t f = 0; f < F; ++f) {
    std::vector<PredictorChoice> candidates;
    auto add = [&](PredictorKind kind, uint32_t d) {
      for (bool nb : {false, true}) candidates.push_back({kind, d, nb});
    };
    if (f == 0) add(PredictorKind::None, 1);
    for (uint32_t d : reference_candidates(q, V, f, po)) add(PredictorKind::Reference, d);
    if (f >= 2) add(PredictorKind::SecondOrder, 1);
    if (options.model_prediction) add(PredictorKind::Model, 1);
    for (int a = 0; a < 3; ++a) {
      double best = HUGE_VAL;
      for (const PredictorChoice& c : candidates) {
        residuals_of(model, trav, q, options, c, f, a, &base, &res);
        const double bits = estimate_residual_bits(res);
        if (bits < best) {
          best = bits;
          plan[size_t(f) * 3 + size_t(a)] = c;
        }
      }
    }
  }
  return plan;
}

}  // namespace dcurve
