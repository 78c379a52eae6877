// The encoder's entry point: an animation in, a .dcrv file out, within a max error.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "encoder/curves/report.h"
#include "encoder/io/frames.h"
#include "encoder/metrics.h"
#include "encoder/render_attributes.h"

namespace dcurve {

// The motion model stored beside the residual layer.
enum class ModelChoice {
  None,  // no PDE model: in-betweens are linear blends of the exact frames
  Pde8,  // 2022 paper's 8-term solutions per curve, axis and segment
  Pde32, // 2024 paper's 32-term solutions
  Pde,   // either, chosen per segment, curve and axis by the rate control
};

// Segment lengths the rate control chooses from (the first wins ties).
constexpr uint32_t kAutoSegmentFrames[] = {8, 4, 16};

constexpr uint32_t kMaxChunkFrames = 4096;

// The smallest tolerance the CLI accepts. What an input reaches also depends on where it
// lies: the decoder's float32 output rounds a coordinate by up to 2^-24 of its magnitude, so
// encode_animation refuses a tolerance below minimum_tolerance(anim) with that figure named.
constexpr double kMinTolerance = 1e-6;
double minimum_tolerance(const Animation& anim);

enum class Profile { Fast, Small };

// EncodeOptions::effort's range and default.
constexpr int kMinEffort = 1, kDefaultEffort = 2, kMaxEffort = 3;

struct EncodeOptions {
  double tolerance = 1e-3;    // max error, fraction of the rest-pose bounding-box diagonal, in (0, 0.5]
  ModelChoice model = ModelChoice::None;
  // PDE model segment length in frames, >= 1; 0: the rate control chooses among
  // kAutoSegmentFrames.
  uint32_t segment_frames = 0;
  uint32_t curve_points = 64;   // target vertices per curve, >= 2
  bool connectivity = true;   // store faces in the file
  // Keep the input's index buffer exactly (triangle order and corner rotation). Off (the
  // default): triangles are stored in the face coder's traversal order (same triangles,
  // same winding, same vertex ids), which codes 1.5-5x smaller, or as given where that is
  // smaller (encoder/face_order.h).
  bool exact_face_order = false;
  // Low-rank (PCA) model of the frames for the residual layer's Model predictor (LRNK):
  // -1 automatic (kept only where the file gets smaller), 0 off, 1..64 that many components
  // always. Not combined with a PDE model (automatic turns off, a count is an error).
  int low_rank = -1;
  // Whether the low-rank choice also screens components around the first frame, besides
  // around the frame average (for studies: false screens the average alone).
  bool low_rank_first_frame = true;
  // Whether it also screens each of those anchors in a common pose (frame poses stored with
  // the model, format 2.5), for frames that turn (for studies: false screens unposed ones).
  bool low_rank_poses = true;
  // Residual grid: 0 chosen by trial encodes (encoder/rate/grid.h; most inputs cost four
  // plain encodes), else the coarsest safe grid made this many times finer, in [1, 16],
  // which skips the trials.
  double grid_refinement = 0;
  // How hard the encoder searches for the grid when grid_refinement is 0, in [1, 3]. 3: the
  // trials walk the refinements (about four whole encodes). 2 (the default): two grids (3x
  // and 8x) side by side, the smaller file wins. 1: one grid 6x finer than the coarsest.
  // The low-rank choice runs in full at every level (encoder/rate/README.md).
  int effort = kDefaultEffort;
  // Which residual coder writes the file. Small (the default): format 3's context-adaptive
  // range coder with per-vertex spatial predictors. Fast: format 4's, built for decode speed
  // (one dense predictor per frame, zstd-coded sparse residuals, short chunks, a low-rank
  // model chosen for it); larger files (encoder/rate/fast_plan.h, format_spec/residual.md).
  Profile profile = Profile::Small;
  // With a PDE model: keep every fitted motion even where it does not pay for its
  // coefficients (in-betweens then follow the model everywhere; the file may be larger).
  // Off: only paying motions are kept, and the file is the one without a PDE model when
  // that is smaller (encoder/rate/motion_choice.h).
  bool keep_all_motions = false;
  // Frames per chunk of the residual layer (a decoder decodes one chunk to reach any of its
  // frames, and holds two decoded chunks): 0 chosen by the encoder, else in [1, 4096].
  uint32_t chunk_frames = 0;
  // In-between rule recorded in the file (codec/common/model.h Inbetween): -1 the one that
  // best predicts held-out input frames (encoder/rate/inbetween_choice.h), else that rule.
  int inbetween = -1;
  // Precision of the render vertices' static attributes (UVs, colours, normals).
  AttributePrecision attributes;
  int threads = 0;            // 0: all hardware threads; output bytes never depend on it
  // Called with the fraction done, in [0, 1] and never decreasing: frames planned against a
  // forecast (encoder/work_meter.h), from the planning threads, one call at a time. May be
  // empty.
  std::function<void(double)> progress;
};

struct EncodeReport {
  uint64_t bytes = 0;
  uint64_t motion_bytes = 0;        // everything but the connectivity section
  uint64_t connectivity_bytes = 0;   // the FACE section, header included
  bool faces_in_coder_order = false; // the FACE section holds the face coder's order
  uint64_t coder_order_connectivity_bytes = 0;  // what the FACE section would take in that order
  uint32_t vertices = 0, frames = 0, segments = 0;
  double bpvf = 0;                  // file bits / (vertices * frames)
  ErrorStats error;                 // measured by decoding the written bytes
  double encode_seconds = 0;
  CurveReport curves{};             // the extracted curves (encoder/curves/report.h)
  std::string curve_fallback;       // why curve extraction fell back to one-vertex curves, or empty
  uint64_t model_bytes = 0;         // SEGS section before zstd, as written (0 without a model)
  uint32_t low_rank_components = 0; // K of the low-rank model in the file, 0 when none
  uint64_t low_rank_bytes = 0;      // its LRNK section as stored, header included
  uint32_t motions_fitted = 0;      // PDE motions (segment, curve, axis) fitted, 0 without a model
  uint32_t motions_kept = 0;        // of them, the non-Zero motions in the file
  double grid_refinement = 0;       // the residual grid: how many times finer than the coarsest safe one
  uint32_t chunk_frames = 0;        // frames per chunk of the residual layer
  Inbetween inbetween = Inbetween::Linear;  // the in-between rule the file records
};

// Encodes `anim` into `out`. The returned error stats come from decoding `out` with the
// runtime decoder (closed loop); the call fails if they break the tolerance.
bool encode_animation(const Animation& anim, const EncodeOptions& options, std::vector<uint8_t>* out,
                      EncodeReport* report, std::string* error);

}  // namespace dcurve
