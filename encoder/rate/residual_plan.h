// Encoder-side choice of the residual predictors: for every frame and axis, the predictor
// (codec/common/predictors.h) whose residuals are estimated to cost the fewest bits.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/residual.h"

namespace dcurve {

struct AxisRun;
class WorkMeter;

struct ResidualPlanOptions {
  // Decoded frames tried as a reference besides the nearest ones, picked by the smallest
  // difference to the frame being coded (animations repeat their poses). >= 0.
  uint32_t extra_references = 3;
  // How far back reference frames are searched, frames, >= 1.
  uint32_t max_reference_distance = 1024;
  // Coding orders tried (the smallest coded wins; residual_plan.cpp's walk_orders plans only
  // those its walk from both ends reaches): 1 is time order; g > 1 codes every g-th frame
  // first and the frames between by recursive midpoints. Not empty, ascending; each >= 1.
  std::vector<uint32_t> gop_sizes = {1, 2, 4, 8, 16};
  // Choose grid values within the tolerance (true) or keep the rounded ones (false).
  bool snap = true;
  // Bits charged for snapping to the edge of the tolerance ball (scaled by the squared
  // distance): trades this frame's bits against the accuracy later predictions start from.
  double distance_weight = 0.0;
  // Candidate predictors: bit (1 << PredictorKind) and bit (1 << SpatialMode) allowed.
  // Frames no allowed kind can serve (frame 0 without None or Model...) fall back to None
  // without spatial correction. For tests and studies.
  uint32_t kinds = ~0u;
  uint32_t spatial_modes = ~0u;
  // Per-cluster predictors (encoder/rate/cluster_plan.h), each layout tried on the chosen
  // coding order (the smallest coded payload wins, one predictor per frame included):
  // traversal positions per cluster (>= 1), clusters per motion map (>= 1) and the similar
  // poses offered per frame (extra_references for this layout's pool; the cluster plan uses
  // at most 6). Small clusters follow the mesh's parts, and different parts find different
  // similar poses, so they are offered more; large ones pay for motion maps on few
  // vertices, and more poses there made files grow.
  struct ClusterLayout {
    uint32_t cluster_size, motion_block;
    uint32_t extra_references = 3;
  };
  std::vector<ClusterLayout> cluster_layouts = {{8, 32, 6}, {512, 1, 3}};
  uint32_t max_candidates = 8;  // candidates a frame may keep, 1..16
  // Geometry frames, whose poses the Fit and Geometric weights are solved on: false names
  // the chunk's first coded frame for every frame, so a decoder solves one weight table per
  // chunk; true the reference pose or the nearest decoded frame, a table per frame.
  bool geometry_per_frame = false;
  // With geometry_per_frame false, choose_plan_and_grid also plans its winning order and
  // layout with a table per frame, and keeps that plan past kPerFrameGeometryGain (--effort 3:
  // a clip that deforms far from its chunk's first frame needs tables of its own poses; the
  // default keeps one table, which decodes about twice as fast).
  bool try_geometry_per_frame = false;
  // Threads for the independent trials (coding orders, cluster layouts); 0 = all cores.
  // The result never depends on it.
  int threads = 0;
  // plan_axis_runs of the plan's model, frames and max_distance, for a caller that plans
  // the same frames on the same grid many times; null: each plan computes them. The result
  // never depends on it.
  const std::vector<std::vector<AxisRun>>* axis_runs = nullptr;
  // Counts every frame planned, for the encode's progress; may be null. The result never
  // depends on it.
  WorkMeter* meter = nullptr;
};

// A table per frame about doubles a decoder's time on a clip whose frames use them (horse-
// gallop: 37 tables, half its decode): worth it only when it shrinks the chunk's payload by
// more than this fraction.
constexpr double kPerFrameGeometryGain = 0.02;

// Estimated cost, bits, of coding `residuals` with an adaptive integer coder: their
// order-0 entropy over exponent classes within each context (contexts[i] < 256, same
// length as residuals) plus the raw mantissa bits. Ranks predictors; does not predict
// file sizes exactly.
double estimate_residual_bits(const std::vector<int64_t>& residuals, const std::vector<uint8_t>& contexts);

// Chooses, for frames coded as one chunk, the coding order, the predictor of every frame (the same for its three axes) and, when
// plan_options.snap is set, the grid values themselves: of the grid points whose decoded
// position lies within max_distance of the input vertex, the one cheapest to code against
// its prediction (the decoder reproduces any grid value exactly, so the error bound holds
// by construction). Frames are walked in coding order, so predictions see chosen values.
//   frames: input positions, model units, one V * 3 vector per frame.
//   max_distance: model units (tolerance * L), > 0.
//   q: in, the rounded grid values (frame-major, within max_distance); out, the chosen ones.
// model supplies counts, faces, curves and the grid (model.residual step and origin).
// Deterministic; cost O(F * candidates * (V + edges)).
PredictorPlan choose_plan_and_grid(const Model& model, const std::vector<std::vector<float>>& frames,
                                   double max_distance, std::vector<int32_t>* q,
                                   const ResidualOptions& options = {},
                                   const ResidualPlanOptions& plan_options = {});

// choose_plan_and_grid with the frames cut into chunks of model.residual.chunk_frames
// (0: one chunk), each planned alone: no predictor reaches into another chunk.
ResidualPlan choose_chunked_plan(const Model& model, const std::vector<std::vector<float>>& frames,
                                 double max_distance, std::vector<int32_t>* q, const ResidualOptions& options = {},
                                 const ResidualPlanOptions& plan_options = {});

// `po` narrowed to what `won` (a plan choose_plan_and_grid made with `po`) chose: its coding
// order's gop size, its cluster layout or none when the one-cluster plan won, and its
// geometry rule (a table per frame or per chunk, no longer tried). Planning with the result
// tries one order, at most one layout and one geometry rule.
ResidualPlanOptions narrow_to_plan(const ResidualPlanOptions& po, const PredictorPlan& won);

// Whether `plan` names more than one geometry frame: planned with a table per frame.
bool geometry_per_frame(const PredictorPlan& plan);

// Per frame, the grid values of each input coordinate that choose_plan_and_grid may snap it
// to (plan_steps.h), as it computes them for these arguments; on up to `threads` threads
// (0: all cores). Memory: 72 bytes per vertex and frame.
std::vector<std::vector<AxisRun>> plan_axis_runs(const Model& model, const std::vector<std::vector<float>>& frames,
                                                 double max_distance, int threads);

}  // namespace dcurve
