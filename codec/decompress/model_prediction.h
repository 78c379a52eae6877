// The Model predictor's values on the residual grid: what the residual layer's Model
// predictor subtracts. They come from the file's low-rank model (LRNK) when it has one,
// else from its PDE motion model. Encoder and decoder both use this code, so the values
// are bit-identical on both sides.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/frame_evaluator.h"
#include "codec/common/low_rank.h"
#include "codec/common/model.h"
#include "codec/common/predictors.h"

namespace dcurve {

// True when some segment of `model` carries a non-Zero motion.
bool has_motion_model(const Model& model);

// The low-rank mean and basis as the model of the K + 1 pseudo-frames whose residual payload
// is model.low_rank.basis_payload (same vertices, faces and curves).
Model low_rank_basis_model(const Model& model);

// True when the residual layer of `model` may use the Model predictor: the file has a
// low-rank model or a PDE motion model (validate_model forbids both at once).
bool has_model_prediction(const Model& model);

// Working space of GridPredictor::frame, reused from frame to frame.
struct PredictionScratch {
  std::vector<float> xyz;  // PDE model positions
  size_t bytes() const { return xyz.capacity() * sizeof(float); }
};

// The Model predictor one frame at a time. Low-rank: the mean and basis are decoded once
// (format_spec/dcrv.md section 10) and each frame evaluated in integer arithmetic. PDE: the
// model alone at frame coordinate x = f, rounded to the grid.
class GridPredictor {
 public:
  // For a validated `model`, which must outlive the predictor. Fails when the tables would
  // exceed `max_values` values or the low-rank basis does not decode or is out of range.
  // traversal (may be null: built for the low-rank basis): build_traversal(model), when the
  // caller has it already.
  // fast_traversal (may be null): fast_traversal(model.faces, V), for a basis coded as a fast
  // payload (format 4), when the caller has it.
  bool build(const Model& model, uint64_t max_values, std::string* error, const Traversal* traversal = nullptr,
             const FastTraversal* fast_traversal = nullptr);
  bool active() const { return active_; }
  // Frame f's V * 3 values (grid units, clamped to +-2^30) into out.
  void frame(uint32_t f, int32_t* out, PredictionScratch* scratch) const;
  // The PDE model's evaluator (empty tables for a low-rank model or none).
  const FrameEvaluator& evaluator() const { return evaluator_; }
  size_t memory_bytes() const { return low_rank_.bytes() + evaluator_.memory_bytes(); }

 private:
  const Model* model_ = nullptr;
  bool active_ = false;
  LowRankTables low_rank_;
  FrameEvaluator evaluator_;
};

// GridPredictor's frames first .. first + count - 1 as a walk's ModelFrameSource (walk frame
// f is frame first + f).
class ChunkModelFrames : public ModelFrameSource {
 public:
  ChunkModelFrames(const GridPredictor& predictor, uint32_t first, PredictionScratch* scratch)
      : predictor_(predictor), first_(first), scratch_(scratch) {}
  void frame(uint32_t f, int32_t* out) const override { predictor_.frame(first_ + f, out, scratch_); }

 private:
  const GridPredictor& predictor_;
  uint32_t first_;
  PredictionScratch* scratch_;
};

// The Model predictor of every frame: out[(f * V + v) * 3 + axis]. For encoders, which
// plan every frame.
bool model_grid_prediction(const Model& model, uint64_t max_values, std::vector<int32_t>* out, std::string* error);

}  // namespace dcurve
