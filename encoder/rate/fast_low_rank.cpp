#include "encoder/rate/fast_low_rank.h"

#include <algorithm>

#include "codec/common/error.h"
#include "codec/common/fast_residual.h"
#include "codec/common/low_rank.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/rate/low_rank.h"

namespace dcurve {
namespace {
// The count is searched with basis values on quarter grid steps, so the prediction the frames
// lean on stays well inside a grid step; then coarser steps, each sqrt(2) times the one
// before, while the file shrinks: a Fit-predicted basis (format 4.3) often codes a coarser
// step in fewer bytes than its frames then lose (horse-gallop's best is near 0.4, a rope's
// 0.25).
constexpr double kBasisStep = 0.25, kStepRatio = 1.41421356237, kMaxBasisStep = 1.0;
// Counts tried in order; the search stops after the file grew twice in a row.
constexpr uint32_t kCounts[] = {0, 2, 4, 6, 8, 12, 16, 24, 32, 48, 64};

// The whole file's bytes with a fast layer coded over `trial` (its payload replaced).
// prediction: the trial's Model prediction, null without a model.
bool fast_file_bytes(Model* trial, const std::vector<std::vector<float>>& frames, const FastLayerOptions& options,
                     const std::vector<int32_t>* prediction, size_t* bytes, std::string* error) {
  if (!encode_fast_layer(trial, frames, options, error, prediction)) return false;
  WriteOptions wo;
  wo.connectivity = !trial->faces.empty();
  *bytes = write_container(*trial, wo).size();
  return true;
}
}  // namespace

bool fast_low_rank_basis(Model* m, std::string* error, const std::vector<int32_t>* values) {
  if (m->low_rank.components == 0) return true;
  std::vector<int32_t> decoded;
  if (values) decoded = *values;
  else if (!decode_residuals(low_rank_basis_model(*m), &decoded, error)) return false;
  std::vector<uint8_t> payload = code_mean_and_basis_fast(*m, &decoded, {});
  if (payload.empty()) return fail(error, "internal error: the low-rank basis does not code as a fast payload");
  m->low_rank.basis_payload = std::move(payload);
  return true;
}

namespace {
// The whole file's bytes with K components on basis step `step` (K = 0: no model) into
// *trial (a copy of base). False with *error set when coding fails; *coded false (and no
// error) when the model leaves the format's ranges.
bool code_trial(const Model& base, const GridComponents& pca, uint32_t K, double step,
                const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
                const FastLayerOptions& options, Model* trial, size_t* bytes, bool* coded, std::string* error) {
  const uint32_t F = base.meta.frame_count;
  const size_t n = size_t(base.meta.vertex_count) * 3;
  *trial = base;
  CodedPayload basis;
  *coded = K == 0 || quantize_low_rank(pca, K, step, 0, options.threads, trial, &rounded, nullptr, nullptr, &basis,
                                       BasisCoding::Fast);
  if (!*coded) return true;
  const std::vector<int32_t> prediction =
      K > 0 ? low_rank_prediction(trial->low_rank, basis.values, F, n) : std::vector<int32_t>();
  return fast_file_bytes(trial, frames, options, K > 0 ? &prediction : nullptr, bytes, error);
}
}  // namespace

bool choose_fast_low_rank(Model* m, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
                          const FastLayerOptions& options, std::string* error) {
  const uint32_t F = m->meta.frame_count;
  const size_t n = size_t(m->meta.vertex_count) * 3;
  Model base = *m;
  base.low_rank = LowRankModel();
  const GridComponents pca =
      grid_components(rounded, F, n, std::min<uint32_t>(kMaxLowRankComponents, F > 1 ? F - 1 : 0), kMeanAnchor);
  Model best, trial;
  size_t best_bytes = SIZE_MAX, bytes = 0;
  uint32_t best_count = 0;
  bool coded = true;
  int worse = 0;
  for (uint32_t K : kCounts) {
    if (K > pca.weights.size() || worse >= 2) break;
    if (!code_trial(base, pca, K, kBasisStep, frames, rounded, options, &trial, &bytes, &coded, error)) return false;
    if (!coded) break;
    if (bytes < best_bytes) {
      best_bytes = bytes;
      best = std::move(trial);
      best_count = K;
      worse = 0;
    } else {
      ++worse;
    }
  }
  for (double step = kBasisStep * kStepRatio; best_count > 0 && step <= kMaxBasisStep; step *= kStepRatio) {
    if (!code_trial(base, pca, best_count, step, frames, rounded, options, &trial, &bytes, &coded, error)) return false;
    if (!coded || bytes >= best_bytes) break;
    best_bytes = bytes;
    best = std::move(trial);
  }
  *m = std::move(best);
  return true;
}

}  // namespace dcurve
