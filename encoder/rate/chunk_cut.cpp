#include "encoder/rate/chunk_cut.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "codec/common/predictors.h"

namespace dcurve {
namespace {

bool inside(uint32_t r, ChunkSpan span) { return r >= span.first && r - span.first < span.count; }

// `c` of a frame of `span`, its frames made chunk-local; the spatial-only fallback (keeping
// a spatial mode that needs no geometry frame) where it reaches outside the span. A geometry
// frame outside the span becomes the chunk's first coded frame (local id `geometry`), as
// planning the chunk on its own would name it, except for that frame itself (kGeometryNone).
constexpr uint32_t kGeometryNone = UINT32_MAX;
PredictorChoice cut_choice(const PredictorChoice& c, ChunkSpan span, PredictorKind fallback, uint32_t geometry) {
  const bool linear = c.kind == PredictorKind::Linear;
  PredictorChoice out = c;
  if (has_reference(c.kind) && (!inside(c.r0, span) || (linear && !inside(c.r1, span))))
    out = {fallback, 0, 0, c.spatial, c.g};
  if (has_reference(out.kind)) {
    out.r0 -= span.first;
    if (linear) out.r1 -= span.first;
  }
  if (uses_geometry(out.spatial)) {
    if (inside(out.g, span)) {
      out.g -= span.first;
    } else if (geometry != kGeometryNone) {
      out.g = geometry;
    } else {
      out.spatial = SpatialMode::Parallelogram;
      out.g = 0;
    }
  }
  return out;
}

FramePredictors cut_frame(const FramePredictors& fp, ChunkSpan span, PredictorKind fallback, uint32_t geometry) {
  FramePredictors out = fp;
  bool motion = false;
  for (std::array<PredictorChoice, 3>& candidate : out.candidates)
    for (PredictorChoice& c : candidate) {
      c = cut_choice(c, span, fallback, geometry);
      motion = motion || c.kind == PredictorKind::Motion;
    }
  if (!motion) out.transforms.clear();
  return out;
}

}  // namespace

ResidualPlan cut_into_chunks(const PredictorPlan& whole, uint32_t F, uint32_t K, bool model_prediction) {
  const PredictorKind fallback = model_prediction ? PredictorKind::Model : PredictorKind::None;
  ResidualPlan out;
  out.chunk_frames = K;
  for (uint32_t c = 0; c < chunk_count(F, K); ++c) {
    const ChunkSpan span = chunk_span(F, K, c);
    PredictorPlan chunk;
    chunk.cluster_size = whole.cluster_size;
    chunk.motion_block = whole.motion_block;
    for (uint32_t f : whole.order)
      if (inside(f, span)) chunk.order.push_back(f - span.first);
    chunk.frames.reserve(span.count);
    const uint32_t first_coded = chunk.order.empty() ? 0 : chunk.order[0];
    for (uint32_t f = span.first; f < span.first + span.count; ++f) {
      const uint32_t local = f - span.first;
      chunk.frames.push_back(cut_frame(whole.frames[f], span, fallback, local == first_coded ? kGeometryNone : first_coded));
    }
    out.chunks.push_back(std::move(chunk));
  }
  return out;
}

}  // namespace dcurve
