// Steps of the residual rate control shared by the per-frame plan (residual_plan.cpp), the
// per-cluster refinement (cluster_plan.cpp) and the PDE model's cost estimates
// (motion_costs.cpp).
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {

// Estimated bits of one residual (grid steps) when choosing among grid points.
int residual_cost(int64_t r);

// The exponent class the entropy estimates count a residual in: 0 for zero, else
// 1 + 2 e + (r < 0) with e = min(floor(log2 |r|), 40), which *exponent receives (0 for zero).
constexpr int kResidualClasses = 2 * 41 + 1;
int residual_class(int64_t r, int* exponent);

// estimate_residual_bits of the residuals added so far (contexts below kContexts), two ways.
// bits(): kept up to date as each is added; it never shrinks when a residual is added, so it
// bounds the estimate of any longer list from below, and the plan drops a candidate
// predictor as soon as it exceeds the best complete candidate's. estimate(): computed from
// the counts exactly as estimate_residual_bits computes it, bit for bit, for ranking.
class RunningBits {
 public:
  static constexpr size_t kContexts = 15;  // the plan's: neighbour class (5) x axis class (3)
  // max_count: the most residuals one context receives between resets.
  explicit RunningBits(size_t max_count);
  void reset();
  void add(size_t context, int64_t r);
  double bits() const { return bits_; }
  double estimate() const;

 private:
  std::vector<double> step_;
  std::array<uint64_t, kContexts * kResidualClasses> hist_{};
  std::array<uint64_t, kContexts> count_{};
  double bits_ = 0, mantissa_ = 0;
};

// Moves qv (a vertex's three grid values) to the admissible grid point (decoded within
// radius, model units, of the input position x) cheapest to code against pred.
void snap_vertex(const ResidualLayer& layer, const float* x, double radius, double distance_weight,
                 const int64_t* pred, int32_t* qv);

// The grid values of one axis whose decoded coordinate lies within radius of the input's
// x (the other axes aside): the run [lo, hi], empty when lo > hi, and its value nearest x.
// They do not depend on the prediction, so a plan computes them once per frame.
struct AxisRun {
  int64_t lo = 0, hi = -1, nearest = 0;
};
// The runs of every coordinate of one frame (xyz: V * 3 input coordinates), in that order.
std::vector<AxisRun> axis_runs(const ResidualLayer& layer, const float* xyz, size_t V, double radius);
// Frame f's runs (xyz: its V * 3 input coordinates): po.axis_runs' when given, else
// computed into *scratch.
const std::vector<AxisRun>& frame_axis_runs(const ResidualPlanOptions& po, const ResidualLayer& layer,
                                            const float* xyz, size_t V, double radius, uint32_t f,
                                            std::vector<AxisRun>* scratch);
// snap_vertex with x's three runs given (runs[a] for axis a, as axis_runs computes them for
// the same layer and radius); the overload above computes them itself.
void snap_vertex(const ResidualLayer& layer, const float* x, const AxisRun* runs, double radius,
                 double distance_weight, const int64_t* pred, int32_t* qv);

// Classes (0..3, 4 for none) of the earlier neighbours' residual magnitudes (clamped, by
// vertex and axis) of traversal position pos, per axis.
void neighbour_classes(const Traversal& t, uint32_t pos, const std::vector<uint8_t>& magnitude, int classes[3]);

// Frame-wide candidate predictors for frame f given the decoded frames (decoded[r] != 0):
// None, Reference and Linear to the nearest decoded frames, Reference to similar poses,
// Model; each with every allowed spatial mode. Never empty.
std::vector<PredictorChoice> candidates_for(const std::vector<int32_t>& q, uint32_t V, uint32_t f,
                                            const std::vector<uint8_t>& decoded, const ResidualOptions& options,
                                            const ResidualPlanOptions& po);

}  // namespace dcurve
