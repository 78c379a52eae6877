// Encoder-side choice of the residual predictors per cluster of vertices: each cluster
// (a run of cluster_size traversal positions, a patch of the mesh) takes the candidate
// estimated cheapest for it, including motion-compensated predictions (an affine map of a
// reference frame per cluster, codec/common/motion_compensation.h) fitted by least squares.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/residual.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {

// Chooses, for the given coding order, every frame's candidates, every cluster's choice
// among them and the motion maps, and (when po.snap) the grid values, like
// choose_plan_and_grid does per frame.
//   frames: input positions, model units, one V * 3 vector per frame.
//   radius: model units, > 0: admissible distance of a grid point from the input.
//   order: a permutation of the frames, the coding order.
//   cluster_size: traversal positions per cluster, >= 1.
//   motion_block: clusters sharing one motion map per candidate, >= 1.
//   max_candidates: predictors a frame may keep, 1..kMaxCandidates.
//   q: in, the rounded grid values (frame-major, within radius); out, the chosen ones.
// Motion candidates are tried when po.kinds allows PredictorKind::Motion; the pool offers
// po.extra_references similar poses per frame (candidates_for), at most
// kMaxGeometryFrames - 2 = 6 so that no frame names more geometry frames than a decoder
// accepts. Deterministic.
PredictorPlan choose_cluster_plan(const Model& model, const std::vector<std::vector<float>>& frames, double radius,
                                  const std::vector<uint32_t>& order, uint32_t cluster_size, uint32_t motion_block,
                                  uint32_t max_candidates, std::vector<int32_t>* q, const ResidualOptions& options,
                                  const ResidualPlanOptions& po);

// Least-squares affine map (fixed point, codec/common/motion_compensation.h) taking the reference
// values `ref` (grid units, v * 3 + axis) of the vertices at traversal positions
// [begin, end) to their input positions `target` (model units, v * 3 + axis) on layer's grid.
MotionTransform fit_motion(const ResidualLayer& layer, const float* target, const int32_t* ref, const Traversal& trav,
                           uint32_t begin, uint32_t end);

}  // namespace dcurve
