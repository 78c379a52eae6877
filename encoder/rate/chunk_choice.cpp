#include "encoder/rate/chunk_choice.h"

#include <algorithm>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "encoder/parallel.h"
#include "encoder/rate/chunk_cut.h"
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

// One candidate length and what measuring it gave.
struct LengthTrial {
  uint32_t K = 0;
  Model model;
  CodedResidual coded;  // RESI only
  std::vector<uint8_t> file;
  std::string error;
};

// t->model's residual layer coded with chunks of t->K frames, planned again.
bool plan_length(LengthTrial* t, const EncodeContext& context, const std::vector<int32_t>* prediction) {
  t->model.residual.chunk_frames = t->K;
  ResidualOptions ro = context.shared;
  ro.model_prediction = prediction;
  t->coded.resi.values = context.rounded;
  t->coded.resi.plan = choose_chunked_plan(t->model, context.frames, context.snap_distance, &t->coded.resi.values, ro, context.plan);
  t->model.residual.payload = encode_residuals(t->model, t->coded.resi.values, t->coded.resi.plan, ro);
  if (t->model.residual.payload.empty()) return fail(&t->error, "internal error: the chunked residual plan is invalid");
  t->file = write_container(t->model, context.write);
  return true;
}

// t->model's residual layer with chunks of t->K frames, its plan cut from `whole`'s (one
// chunk of every frame) and coded with the same values.
bool cut_length(LengthTrial* t, const CodedPayload& whole, const EncodeContext& context,
                const std::vector<int32_t>* prediction) {
  const uint32_t F = t->model.meta.frame_count;
  t->model.residual.chunk_frames = t->K;
  ResidualOptions ro = context.shared;
  ro.model_prediction = prediction;
  t->coded.resi.plan = cut_into_chunks(whole.plan.chunks[0], F, t->K, prediction != nullptr);
  t->coded.resi.values = whole.values;
  for (uint32_t c = 0; c < t->coded.resi.plan.chunks.size(); ++c)
    if (!plan_is_valid(t->coded.resi.plan.chunks[c], chunk_span(F, t->K, c).count, t->model.meta.vertex_count, ro))
      return fail(&t->error, "internal error: a plan cut into chunks is invalid");
  t->model.residual.payload = encode_residuals(t->model, t->coded.resi.values, t->coded.resi.plan, ro);
  if (t->model.residual.payload.empty()) return fail(&t->error, "internal error: the cut residual plan does not code");
  t->file = write_container(t->model, context.write);
  return true;
}

// The shortest length whose file is within kChunkSlack of the smallest.
size_t pick_length(const std::vector<LengthTrial>& trials) {
  size_t smallest = SIZE_MAX;
  for (const LengthTrial& t : trials) smallest = std::min(smallest, t.file.size());
  size_t i = 0;
  while (double(trials[i].file.size()) > double(smallest) * (1 + kChunkSlack)) ++i;
  return i;
}

}  // namespace

bool choose_chunk_frames(Model* model, CodedResidual* coded, const EncodeContext& context, ChunkTrial how,
                         std::vector<uint8_t>* file, std::string* error) {
  const uint32_t F = model->meta.frame_count;
  if (has_model_prediction(*model) == coded->prediction.empty())
    return fail(error, "internal error: the chunk choice lacks the Model prediction");
  const std::vector<int32_t>* predicted = coded->prediction.empty() ? nullptr : &coded->prediction;
  const uint32_t current = std::min(std::max(model->residual.chunk_frames, 1u), F);
  // Cutting needs the plan of one chunk of every frame; any other is planned again.
  const bool cut = how == ChunkTrial::Cut && current == F && coded->resi.plan.chunks.size() == 1;
  std::vector<LengthTrial> trials;
  for (uint32_t K : candidate_lengths(F)) trials.push_back({K, *model, {}, {}, {}});
  // The lengths are measured side by side (each may use the cores the others leave idle);
  // each writes its own slot.
  parallel_for(trials.size(), context.plan.threads, [&](size_t i) {
    LengthTrial& t = trials[i];
    if (t.K == current) {  // already coded so
      t.file = write_container(*model, context.write);
    } else if (!(cut ? cut_length(&t, coded->resi, context, predicted) : plan_length(&t, context, predicted))) {
      t.file.clear();
    }
  });
  for (const LengthTrial& t : trials)
    if (t.file.empty()) return fail(error, t.error);
  LengthTrial& chosen = trials[pick_length(trials)];
  if (chosen.K == current) {
    file->swap(chosen.file);
    return true;
  }
  // A cut plan only measured the length: the file gets a plan of its own chunks.
  if (cut && !plan_length(&chosen, context, predicted)) return fail(error, chosen.error);
  *model = std::move(chosen.model);
  coded->resi = std::move(chosen.coded.resi);
  file->swap(chosen.file);
  return true;
}

}  // namespace dcurve
