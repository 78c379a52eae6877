// What an open decoder shares among its cursors, and a cursor's window of decoded chunks.
// Internal to the decoder library.
#pragma once
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "chunk_source.h"
#include "codec/common/inbetween.h"
#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"
#include "codec/decompress/fast_residual_decoder.h"
#include "codec/decompress/model_prediction.h"
#include "dcurve.hpp"

namespace dcurve {

// Immutable after open.
// Render vertices as a game draws them (REND), built at open: the attributes as floats and
// the groups of render vertices that share a computed normal.
struct RenderState {
  std::vector<float> attributes[kAttributeSemanticCount];  // empty when the file has none
  uint32_t components[kAttributeSemanticCount] = {};
  std::vector<uint32_t> normal_group;  // per render vertex
  std::vector<uint32_t> corner_group;  // per corner of the faces: its render vertex's normal group
  uint32_t normal_groups = 0;
  std::vector<uint32_t> group_faces;   // render triangles by group (3 ids each); empty without groups
  std::vector<uint32_t> group_first;   // group g's triangles: [group_first[g], group_first[g + 1])
  size_t memory_bytes() const;
};
// Builds it from model->render (the file must have passed validate_model), then frees the
// attributes' quantized values, which nothing reads again.
void build_render_state(Model* model, RenderState* state);

struct SharedState {
  Model model;          // residual.payload: the chunk index only
  ResidualIndex index;  // empty without a residual layer
  Traversal traversal;  // the residual layer's vertex order and neighbours (format 3)
  FastTraversal fast_traversal;  // format 4's
  GridPredictor predictor;
  RenderState render;
  std::unique_ptr<ChunkSource> chunks;

  bool has_residual() const { return !index.chunks.empty(); }
  bool fast() const { return index.version == fast_residual::kPayloadVersion; }
  size_t memory_bytes() const;
};

// One decoded chunk and the frame before it (for the blend across a chunk boundary), and
// the buffers decoding reuses: memory for K + 1 frames, whatever the clip's length; with a
// cubic in-between rule also the corrections of the up to six frames around the one evaluated.
class ChunkWindow {
 public:
  explicit ChunkWindow(const SharedState& shared);
  // The in-between rule evaluate uses: the file's (META) until set.
  void set_inbetween(Inbetween rule) { rule_ = uint8_t(rule) < kInbetweenCount ? rule : Inbetween::Linear; }
  // Positions at frame coordinate x into out (vertex_count * 3 floats).
  bool evaluate(double x, float* out, Error* error);
  size_t memory_bytes() const;
  uint32_t frame_count() const { return shared_.model.meta.frame_count; }

 private:
  // Grid values of frame f, decoding its chunk when it is not the one held; null with the
  // error set when the chunk cannot be read or decoded. Invalidates earlier pointers unless
  // f is in the chunk held.
  const int32_t* frame_values(uint32_t f, Error* error);
  bool decode_chunk(uint32_t c, Error* error);
  // Fast payloads (format 4): frames decoded one at a time into a ring of the last three.
  const int32_t* fast_frame_values(uint32_t f, Error* error);
  bool open_fast_chunk(uint32_t c, Error* error);
  bool decode_fast_frame(Error* error);
  struct FrameSlot;
  FrameSlot* fast_target(uint32_t f);
  const int32_t* model_values(uint32_t f);
  // Frame f's correction in the segment of `place`, kept in a stencil slot: the frames of one
  // cubic in-between stay valid together, and the in-betweens around f reuse it. Reuses a
  // slot whose frame is outside [lo, hi] or whose segment is another.
  const float* stencil_correction(const FrameEvaluator::Place& place, uint32_t f, uint32_t lo, uint32_t hi,
                                  Error* error);
  bool evaluate_cubic(const FrameEvaluator::Place& place, float* out, Error* error);

  const SharedState& shared_;
  uint32_t chunk_ = UINT32_MAX;  // the chunk whose frames `values_` holds
  std::vector<int32_t> values_;  // frame-major
  uint32_t kept_frame_ = UINT32_MAX;  // the frame `kept_` holds
  std::vector<int32_t> kept_;
  Inbetween rule_;
  struct StencilSlot {
    uint32_t frame = UINT32_MAX;
    size_t span = 0;
    std::vector<float> correction;
  };
  StencilSlot stencil_[kInbetweenStencil];
  ResidualWorkspace workspace_;
  struct FrameSlot {
    uint32_t frame = UINT32_MAX;
    std::vector<int32_t> values;
  };
  FastChunkDecoder fast_;
  uint32_t fast_chunk_ = UINT32_MAX;  // the chunk fast_ decodes
  FrameSlot ring_[3];                 // the last three frames decoded
  FrameSlot model_[2];                // Model predictions of the last two frames asked for
  std::vector<uint8_t> read_buffer_;
  std::vector<float> scratch_;
  PredictionScratch prediction_scratch_;
};

// What a Decoder holds (decoder.cpp opens it, render.cpp answers the render calls).
struct Decoder::Impl {
  SharedState shared;
  // The window behind Decoder::evaluate: one call at a time.
  mutable std::mutex mutex;
  mutable std::unique_ptr<ChunkWindow> window;
  bool rule_set = false;  // the internal window uses `rule`, not the file's
  Inbetween rule = Inbetween::Linear;
};

}  // namespace dcurve
