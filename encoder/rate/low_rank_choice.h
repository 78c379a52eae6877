// Rate control of the low-rank model: whether the file carries one (LRNK) for the residual
// layer's Model predictor, with how many components and how coarse, judged by whole-file
// bytes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/common/residual.h"
#include "codec/compress/container_writer.h"
#include "encoder/rate/coded_residual.h"
#include "encoder/rate/encode_context.h"
#include "encoder/rate/low_rank.h"

namespace dcurve {

// A low-rank model as a choice made elsewhere (by an encode of part of the clip): which
// anchor, how many components, how coarse.
struct LowRankPick {
  uint32_t components = 0;          // 0: no model
  uint32_t anchor = kMeanAnchor;    // GridComponents::anchor: the frame average or a frame
  bool posed = false;               // the anchor carried into a common pose
  double basis_step = 0;            // grid units
  bool geometry_per_frame = false;  // its trial's plan kept a Fit weight table per frame
};

struct LowRankChoiceOptions {
  // -1: automatic (kept only when the file gets smaller); 0: never; K in 1..64: always use K
  // components (for studies; the file may get larger).
  int components = -1;
  // Full residual encodes tried with a low-rank model per anchor (the frame average, frame 0),
  // best screened candidates first (one per component count), >= 1. Once the screening
  // refines the best count's step, the first trial is the one that wins, so a second one
  // costs a full residual encode and does not change the file.
  uint32_t max_trials = 1;
  // Also screen components around the first frame, besides around the frame average.
  bool first_frame_anchor = true;
  // Also screen each anchor's components in a common pose (frame poses stored with the
  // model, format 2.5) when the frames turn far enough against frame 0 for it to matter.
  bool posed_anchors = true;
  // Screen the counts whose section outweighs today's residual payload at the first basis
  // step at coarser steps (upwards, while each saves at least half its section), and give
  // the best of them a trial of its own.
  bool rescue_cut_counts = true;
  // When set (components must stay -1): no screening; only this model gets a full trial,
  // kept when the whole file gets smaller.
  const LowRankPick* follow = nullptr;
};

struct LowRankChoiceReport {
  LowRankPick kept;              // the model kept (components 0 when none)
  uint32_t screened = 0, trials = 0;
  bool rescued = false;          // the model kept is one of those rescue_cut_counts screened
  uint64_t bytes_without = 0;    // the whole file without a low-rank model
  uint64_t bytes = 0;            // the whole file kept (bytes_without when it has no model)
};

// The residual layer of a finished encode as the step that planned it left it: the plan and
// the grid values (frame-major) its payload codes.
struct PlannedResidual {
  const ResidualPlan& plan;
  const std::vector<int32_t>& values;
};

// `model` holds a finished encode of the context's frames without a low-rank model (residual
// payload coded, no PDE motions), planned as `planned` says. Screens low-rank models by a
// cheap estimate, encodes the residual with the promising ones and keeps the smallest whole
// file in `model` (low_rank and residual.payload replaced); when it keeps one, *kept (may be
// null) receives what its payload codes, and is left alone otherwise. The result never
// depends on the context's threads, weight tables or traversal. False only on an internal
// error.
bool choose_low_rank(Model* model, const PlannedResidual& planned, const EncodeContext& context,
                     const LowRankChoiceOptions& options, LowRankChoiceReport* report, std::string* error,
                     CodedResidual* kept = nullptr);

// About how many frames choose_low_rank plans for F frames (screening plans and full
// trials; the count depends on the input), for an encode's progress forecast.
uint64_t forecast_low_rank_frames(uint32_t F);

}  // namespace dcurve
