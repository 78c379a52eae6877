// The residual layer: integer grid positions of every input frame, coded against
// predictions chosen per frame and axis, with a context-adaptive range coder. Encoder and
// decoder share this file so the round trip is bit-exact. format_spec/residual.md is the
// byte layout.
//
// Grid positions are laid out frame-major: q[(f * V + v) * 3 + axis].
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"
#include "codec/motion_compensation.h"
#include "codec/predictors.h"

namespace dcurve {

// The predictors of one frame. Vertices are split into clusters of cluster_size
// consecutive traversal positions (breadth-first over the mesh, so each is a patch); every
// cluster uses one of the frame's candidates.
struct FramePredictors {
  std::vector<std::array<PredictorChoice, 3>> candidates;  // 1..kMaxCandidates, one predictor per axis
  std::vector<uint8_t> cluster_candidate;  // per cluster, index into candidates; empty: all 0
  // Motion maps, one per (motion block, candidate): entry block * candidates.size() + j,
  // the rows of candidate j's Motion axes (other rows unused). Empty when no candidate
  // uses Motion.
  std::vector<MotionTransform> transforms;
};
constexpr uint32_t kMaxCandidates = 16;
// Distinct Geometric and Fit geometry frames among one frame's candidates: each costs the decoder
// a table of weights (SpatialWeightsCache holds this many), so the bound keeps decoding
// linear in the frame's size whatever the file asks for.
constexpr uint32_t kMaxGeometryFrames = 8;

// Whether the candidates of one frame name at most kMaxGeometryFrames geometry frames.
bool geometry_frames_within_bound(const FramePredictors& fp);

// How frames are coded: in which order, each cluster and axis with which predictor.
struct PredictorPlan {
  std::vector<uint32_t> order;  // a permutation of [0, frame_count): coding order
  uint32_t cluster_size = UINT32_MAX;  // traversal positions per cluster, >= 1
  // Clusters per motion block, >= 1: a Motion candidate's map is shared by the clusters of
  // a block (maps cost a dozen numbers, so they cover more vertices than a choice does).
  uint32_t motion_block = 1;
  std::vector<FramePredictors> frames;  // indexed by frame, not position
  // Bytes of the range-coded stream each frame's values took, indexed by frame: filled by
  // decoding (decode_residuals, decode_predictor_plan with clusters), empty otherwise. For
  // reports: the coder reads a few bytes ahead, so a frame's count is within +-4 bytes.
  std::vector<uint32_t> stream_bytes;
};

// Number of clusters of V vertices: ceil(V / cluster_size) (cluster_size >= 1).
inline uint32_t cluster_count(uint32_t V, uint32_t cluster_size) {
  return cluster_size == 0 ? 0 : uint32_t((uint64_t(V) + cluster_size - 1) / cluster_size);
}

// Number of motion blocks of a frame with V vertices.
inline uint32_t motion_block_count(uint32_t V, const PredictorPlan& plan) {
  const uint32_t clusters = cluster_count(V, plan.cluster_size);
  return plan.motion_block == 0 ? 0 : uint32_t((uint64_t(clusters) + plan.motion_block - 1) / plan.motion_block);
}

// A plan with one candidate per frame (choices: entry f * 3 + axis) and one cluster.
PredictorPlan uniform_plan(const std::vector<uint32_t>& order, const std::vector<PredictorChoice>& choices);

// The plan used when the caller has none: time order, frame 0 from its mesh neighbours,
// every later frame as the previous frame plus the neighbours' motion.
PredictorPlan default_predictor_plan(uint32_t frame_count);

// Whether `plan` fits the model's counts, every choice refers only to frames coded before
// it, cluster indices and motion maps are in range.
bool plan_is_valid(const PredictorPlan& plan, uint32_t frame_count, uint32_t vertex_count,
                   const ResidualOptions& options);

// Codes the grid positions `q` (frame_count * vertex_count * 3 values, each an int32) of
// `model` into a payload for model.residual.payload. `model` supplies counts, faces (the
// neighbour structure; leave them empty when the file will not store them) and curves.
// `plan` (plan_is_valid) picks the order and predictors; null means default_predictor_plan.
// An invalid plan or mismatched sizes are a caller bug: returns an empty vector.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q,
                                      const PredictorPlan* plan = nullptr,
                                      const ResidualOptions& options = {});

// Reverses encode_residuals. `q` receives frame_count * vertex_count * 3 values. Returns
// false with a message on a malformed or corrupted payload (a checksum of the decoded
// values is verified); never reads outside the payload. `plan`, when not null, receives the
// complete plan the payload was coded with (per-cluster choices and motion maps included).
bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error,
                      const ResidualOptions& options = {}, PredictorPlan* plan = nullptr);

// Reads the predictor table of model.residual.payload (for reports and tools). The
// per-cluster choices and motion maps live in the coded stream: with `with_clusters` the
// whole payload is decoded to fill them, else they are left empty.
bool decode_predictor_plan(const Model& model, PredictorPlan* plan, std::string* error,
                           const ResidualOptions& options = {}, bool with_clusters = false);

// Grid value -> model units, exactly as the decoder converts it (float32 output).
inline float grid_to_model(const ResidualLayer& layer, int axis, int64_t value) {
  return float(layer.origin[axis] + layer.step * double(value));
}

// The residuals encode_residuals would code, in coding order (frame in plan order,
// traversal position, axis): for measuring the entropy coder against general-purpose compressors.
// `plan` must be complete (from the encoder, or decode_predictor_plan with with_clusters);
// empty when it uses Motion without its maps.
std::vector<int64_t> residual_values(const Model& model, const std::vector<int32_t>& q, const PredictorPlan& plan,
                                     const ResidualOptions& options = {});

}  // namespace dcurve
