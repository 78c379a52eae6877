// The residual layer: integer grid positions of every input frame, coded against
// predictions chosen per frame and axis, with a context-adaptive range coder.
// format_spec/residual.md is the byte layout. This header is what encoder and decoder both
// use: the plan of predictors, the chunks and their index. The walk both sides run, so the
// round trip is bit-exact, is codec/common/residual_walk.h; codec/compress/residual_encoder.h
// writes the payload, codec/decompress/residual_decoder.h reads it.
//
// Grid positions are laid out frame-major: q[(f * V + v) * 3 + axis].
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/motion_compensation.h"
#include "codec/common/predictors.h"

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

// The frames of a residual layer are coded in chunks of K consecutive frames (the last may
// be shorter). A chunk's predictors reach only frames of the same chunk and data every chunk
// can reach (the Model predictor), so a decoder decodes any chunk alone. Chunk c codes
// frames [c K, min(F, (c + 1) K)); inside it, frame ids are local (0 = its first frame).
struct ResidualPlan {
  uint32_t chunk_frames = 0;           // K >= 1
  std::vector<PredictorPlan> chunks;   // one per chunk, chunk-local frame ids
};

inline uint32_t chunk_count(uint32_t frame_count, uint32_t chunk_frames) {
  return chunk_frames == 0 ? 0 : uint32_t((uint64_t(frame_count) + chunk_frames - 1) / chunk_frames);
}
// Frames of chunk c: [first, first + count).
struct ChunkSpan {
  uint32_t first = 0, count = 0;
};
inline ChunkSpan chunk_span(uint32_t frame_count, uint32_t chunk_frames, uint32_t c) {
  const uint64_t first = uint64_t(c) * chunk_frames;
  const uint64_t end = std::min<uint64_t>(frame_count, first + chunk_frames);
  return {uint32_t(first), end > first ? uint32_t(end - first) : 0u};
}

// A plan of one chunk holding every frame: what a file without chunking would code.
ResidualPlan single_chunk_plan(const PredictorPlan& plan);
// default_predictor_plan in every chunk of K frames.
ResidualPlan default_chunked_plan(uint32_t frame_count, uint32_t chunk_frames);

// One frame of a ResidualPlan in coding order (chunk after chunk), by its whole-animation
// id: for reports and rate estimates that look at frames, not chunks.
struct CodedFrame {
  uint32_t frame = 0;
  const PredictorPlan* chunk = nullptr;
  const FramePredictors* predictors = nullptr;
};
std::vector<CodedFrame> coded_frames(const ResidualPlan& plan);

// Where each chunk's bytes lie in the chunk data that follows the payload's index
// (format_spec/residual.md): offsets from the start of that data.
struct ChunkEntry {
  uint64_t offset = 0, size = 0;
  uint32_t crc = 0;  // CRC-32C of the chunk's bytes
};
struct ResidualIndex {
  uint8_t version = 0;  // of the payload: residual_walk::kOldestFormatVersion..kFormatVersion
  bool from_faces = false;
  uint32_t chunk_frames = 0;
  std::vector<ChunkEntry> chunks;
  size_t index_bytes = 0;   // bytes of the payload before the chunk data
  uint64_t data_bytes = 0;  // bytes of chunk data the index describes (the last chunk's end)
};

// Reused buffers of chunk decoding: after the first chunk, decoding allocates nothing more
// for chunks no larger than it (bar the spatial weight tables of Geometric and Fit frames).
struct ResidualWorkspace {
  std::vector<int8_t> residuals;
  std::vector<int64_t> base;
  std::vector<int32_t> model_frame;
  std::vector<uint8_t> block_flags, previous_block_flags;  // zero-block flags of two frames
  PredictorPlan plan;
  size_t bytes() const {
    return residuals.capacity() + base.capacity() * sizeof(int64_t) + model_frame.capacity() * sizeof(int32_t) +
           block_flags.capacity() + previous_block_flags.capacity();
  }
};

// Grid value -> model units, exactly as the decoder converts it (float32 output).
inline float grid_to_model(const ResidualLayer& layer, int axis, int64_t value) {
  return float(layer.origin[axis] + layer.step * double(value));
}

}  // namespace dcurve
