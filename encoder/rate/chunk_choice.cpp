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
// null), planned with `plan`; its plan and values in *coded, its file in *file.
bool code_with_length(Model* trial, CodedResidual* coded, uint32_t K, const EncodeContext& context,
                      const std::vector<int32_t>* prediction, const ResidualPlanOptions& plan,
                      std::vector<uint8_t>* file, std::string* error) {
  trial->residual.chunk_frames = K;
  ResidualOptions ro = context.shared;
  ro.model_prediction = prediction;
  coded->resi.values = context.rounded;
  coded->resi.plan = choose_chunked_plan(*trial, context.frames, context.snap_distance, &coded->resi.values, ro, plan);
  trial->residual.payload = encode_residuals(*trial, coded->resi.values, coded->resi.plan, ro);
  if (trial->residual.payload.empty()) return fail(error, "internal error: the chunked residual plan is invalid");
  *file = write_container(*trial, context.write);
  return true;
}

}  // namespace

bool choose_chunk_frames(Model* model, CodedResidual* coded, const EncodeContext& context, std::vector<uint8_t>* file,
                         std::string* error) {
  const uint32_t F = model->meta.frame_count;
  if (has_model_prediction(*model) == coded->prediction.empty())
    return fail(error, "internal error: the chunk choice lacks the Model prediction");
  const std::vector<int32_t>* predicted = coded->prediction.empty() ? nullptr : &coded->prediction;
  const std::vector<uint32_t> lengths = candidate_lengths(F);
  std::vector<Model> trials(lengths.size(), *model);
  std::vector<CodedResidual> trials_coded(lengths.size());  // RESI only
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
    if (!code_with_length(&trials[i], &trials_coded[i], lengths[i], context, predicted, each, &files[i], &errors[i]))
      files[i].clear();
  });
  for (size_t i = 0; i < lengths.size(); ++i)
    if (files[i].empty()) return fail(error, errors[i]);
  size_t smallest = SIZE_MAX;
  for (const std::vector<uint8_t>& f : files) smallest = std::min(smallest, f.size());
  for (size_t i = 0; i < lengths.size(); ++i)
    if (double(files[i].size()) <= double(smallest) * (1 + kChunkSlack)) {
      if (lengths[i] != current) {
        *model = std::move(trials[i]);
        coded->resi = std::move(trials_coded[i].resi);
      }
      file->swap(files[i]);
      return true;
    }
  return fail(error, "internal error: no chunk length chosen");
}

}  // namespace dcurve
