#include "encoder/rate/chunk_choice.h"

#include <algorithm>

#include "codec/common/error.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "encoder/parallel.h"
#include "encoder/rate/residual_plan.h"

namespace dcurve {
namespace {

// The candidate lengths for F frames, shortest first: each of kChunkCandidates below F,
// then F (one chunk) for a short clip.
std::vector<uint32_t> candidate_lengths(uint32_t F) {
  std::vector<uint32_t> out;
  for (uint32_t K : kChunkCandidates)
    if (K < F) out.push_back(K);
  if (F <= kMaxWholeClipFrames || out.empty()) out.push_back(F);
  return out;
}

// *trial's residual layer coded with chunks of K frames (its Model predictions given or
// null), planned with `plan`; its file.
bool code_with_length(Model* trial, uint32_t K, const EncodeContext& context, const std::vector<int32_t>* prediction,
                      const ResidualPlanOptions& plan, std::vector<uint8_t>* file, std::string* error) {
  trial->residual.chunk_frames = K;
  ResidualOptions ro = context.shared;
  ro.model_prediction = prediction;
  std::vector<int32_t> q = context.rounded;
  const ResidualPlan chunked = choose_chunked_plan(*trial, context.frames, context.snap_distance, &q, ro, plan);
  trial->residual.payload = encode_residuals(*trial, q, chunked, ro);
  if (trial->residual.payload.empty()) return fail(error, "internal error: the chunked residual plan is invalid");
  *file = write_container(*trial, context.write);
  return true;
}

}  // namespace

bool choose_chunk_frames(Model* model, const EncodeContext& context, std::vector<uint8_t>* file, std::string* error) {
  const uint32_t F = model->meta.frame_count;
  std::vector<int32_t> prediction;
  if (has_model_prediction(*model) && !model_grid_prediction(*model, UINT64_MAX, &prediction, error)) return false;
  const std::vector<int32_t>* predicted = prediction.empty() ? nullptr : &prediction;
  const std::vector<uint32_t> lengths = candidate_lengths(F);
  std::vector<Model> trials(lengths.size(), *model);
  std::vector<std::vector<uint8_t>> files(lengths.size());
  const uint32_t current = std::min(std::max(model->residual.chunk_frames, 1u), F);
  // The lengths are coded side by side, sharing the threads; each writes its own slot.
  ResidualPlanOptions each = context.plan;
  each.threads = threads_per_job(context.plan.threads, lengths.size());
  std::vector<std::string> errors(lengths.size());
  parallel_for(lengths.size(), context.plan.threads, [&](size_t i) {
    if (lengths[i] == current) {  // already coded so
      files[i] = write_container(*model, context.write);
      return;
    }
    if (!code_with_length(&trials[i], lengths[i], context, predicted, each, &files[i], &errors[i])) files[i].clear();
  });
  for (size_t i = 0; i < lengths.size(); ++i)
    if (files[i].empty()) return fail(error, errors[i]);
  size_t smallest = SIZE_MAX;
  for (const std::vector<uint8_t>& f : files) smallest = std::min(smallest, f.size());
  for (size_t i = 0; i < lengths.size(); ++i)
    if (double(files[i].size()) <= double(smallest) * (1 + kChunkSlack)) {
      *model = std::move(trials[i]);
      file->swap(files[i]);
      return true;
    }
  return fail(error, "internal error: no chunk length chosen");
}

}  // namespace dcurve
