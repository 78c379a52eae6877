#include "encoder/rate/grid.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "encoder/parallel.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {

namespace {

// Cube side 2 * max_distance / sqrt(3): the coarsest grid whose rounding stays within the
// bound (half-diagonal s * sqrt(3) / 2), shrunk by a margin that absorbs float32 output rounding.
double coarsest_step(double max_distance) { return 2.0 * max_distance / std::sqrt(3.0) * (1.0 - 1e-3); }

// The finer grid choose_grid tries, this much finer than the coarsest. The residual layer
// keeps a prediction wherever it lies within the tolerance ball, so its bits go to the
// predictions that leave the ball. Predictions are built from decoded grid values and
// rounded to the grid, so each carries up to half a step of rounding per axis; on the
// coarsest grid the ball reaches only 0.87 steps, and that rounding alone pushes slow,
// smooth motion out of it. A finer grid shrinks the rounding against the ball, at the price
// of larger residuals where a prediction does leave and of more bits for frames coded from
// nothing, which fast motion pays for (elastic-cow, tolerance 1e-4). 1.4 and 1.5 were
// measured (whole files at 1e-3); 1.5 codes the XPBD rope 40 % smaller.
constexpr double kGridRefinement = 1.5;

// Frames of the trial encodes: the whole animation up to kTrialVertexFrames vertices x
// frames (the sheet scene's 90 frames favour the finer grid, its middle 33 the coarsest),
// else a run of kTrialFrames or more from its middle, long enough for the hierarchical
// order below.
constexpr uint32_t kTrialFrames = 33;
constexpr uint64_t kTrialVertexFrames = 500000;

}  // namespace

ResidualLayer make_grid(const Animation& anim, double max_distance, double refinement) {
  ResidualLayer r;
  double extent = 0;
  for (int a = 0; a < 3; ++a) {
    double lo = anim.frames[0][a], hi = lo;
    for (const auto& fr : anim.frames)
      for (size_t i = a; i < fr.size(); i += 3) {
        lo = std::min(lo, double(fr[i]));
        hi = std::max(hi, double(fr[i]));
      }
    r.origin[a] = lo;
    extent = std::max(extent, hi - lo);
  }
  r.step = coarsest_step(max_distance) / std::max(refinement, 1.0);
  // Grid values must fit quantize_to_grid's range (2^30); a tolerance that tiny against
  // the motion's extent keeps the coarsest grid.
  if (extent / r.step + 1 > double(INT32_MAX) / 2) r.step = coarsest_step(max_distance);
  return r;
}

ResidualLayer choose_grid(const Model& model, const Animation& anim, double max_distance, int threads) {
  const uint32_t F = uint32_t(anim.frames.size());
  const uint64_t wanted = std::max<uint64_t>(kTrialFrames, kTrialVertexFrames / std::max(anim.vertex_count, 1u));
  const uint32_t count = uint32_t(std::min<uint64_t>(F, wanted)), first = (F - count) / 2;
  Animation part;
  part.vertex_count = anim.vertex_count;
  part.frames.assign(anim.frames.begin() + first, anim.frames.begin() + first + count);
  const double refinements[2] = {1.0, kGridRefinement};
  ResidualLayer grids[2];
  size_t bytes[2] = {SIZE_MAX, SIZE_MAX};
  parallel_for(2, threads, [&](size_t i) {
    grids[i] = make_grid(anim, max_distance, refinements[i]);
    Model trial;
    trial.meta = model.meta;
    trial.meta.frame_count = count;
    trial.faces = model.faces;
    trial.curves = model.curves;
    trial.residual = grids[i];
    std::vector<int32_t> q;
    if (!quantize_to_grid(part, grids[i], &q, nullptr)) return;
    // One hierarchical order without clusters: it ranks the grids like the whole search
    // (horse-gallop, chicken-crossing, crane, cloth-sphere, elastic-cow, the rope scenes)
    // at a fraction of its cost.
    ResidualPlanOptions po;
    po.gop_sizes = {8};
    po.cluster_layouts.clear();
    po.threads = 1;
    const PredictorPlan plan = choose_plan_and_grid(trial, part.frames, max_distance * (1.0 - 1e-6), &q, {}, po);
    bytes[i] = encode_residuals(trial, q, &plan).size();
  });
  return bytes[1] < bytes[0] ? grids[1] : grids[0];
}

bool quantize_to_grid(const Animation& anim, const ResidualLayer& grid, std::vector<int32_t>* q,
                      std::string* error) {
  const size_t n = size_t(anim.vertex_count) * 3;
  q->resize(anim.frames.size() * n);
  for (size_t f = 0; f < anim.frames.size(); ++f)
    for (size_t i = 0; i < n; ++i) {
      double g = std::nearbyint((double(anim.frames[f][i]) - grid.origin[i % 3]) / grid.step);
      if (!(g >= 0 && g <= double(INT32_MAX) / 2)) {
        if (error) *error = "tolerance too small for the motion's range (grid values overflow)";
        return false;
      }
      (*q)[f * n + i] = int32_t(g);
    }
  return true;
}

}  // namespace dcurve
