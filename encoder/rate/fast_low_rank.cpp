#include "encoder/rate/fast_low_rank.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/error.h"
#include "codec/common/fast_residual.h"
#include "codec/common/low_rank.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/rate/low_rank.h"
#include "encoder/work_meter.h"

namespace dcurve {
namespace {
// The count is searched with basis values on quarter grid steps, so the prediction the frames
// lean on stays well inside a grid step; then coarser steps, each sqrt(2) times the one
// before, while the file shrinks: a Fit-predicted basis (format 4.3) often codes a coarser
// step in fewer bytes than its frames then lose (horse-gallop's best is near 0.4, a rope's
// 0.25).
constexpr double kBasisStep = 0.25, kStepRatio = 1.41421356237, kMaxBasisStep = 1.0;
// The counts a search may try. The file's size is not convex in the count (the sheet scene:
// a few components cost more than none, 48 far less), so every other one is tried first,
// then the two beside the best.
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

namespace {
// The trials of one count search over a fixed model and input.
class CountSearch {
 public:
  CountSearch(const Model& base, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
              const FastLayerOptions& options)
      : base_(base), frames_(frames), rounded_(rounded), options_(options),
        pca_(grid_components(rounded, base.meta.frame_count, size_t(base.meta.vertex_count) * 3,
                             std::min<uint32_t>(kMaxLowRankComponents,
                                                base.meta.frame_count > 1 ? base.meta.frame_count - 1 : 0),
                             kMeanAnchor)) {}

  uint32_t max_count() const { return uint32_t(pca_.weights.size()); }
  // Codes K components on `step` (K <= max_count()); keeps the trial when its file is the
  // smallest so far. *coded: false when the model leaves the format's ranges.
  bool try_count(uint32_t K, double step, bool* smaller, bool* coded, std::string* error) {
    size_t bytes = 0;
    if (!code_trial(base_, pca_, K, step, frames_, rounded_, options_, &trial_, &bytes, coded, error)) return false;
    if (options_.meter) options_.meter->add(base_.meta.frame_count);
    *smaller = *coded && bytes < best_bytes_;
    if (*smaller) {
      best_bytes_ = bytes;
      best_ = std::move(trial_);
      best_count_ = K;
    }
    return true;
  }
  uint32_t best_count() const { return best_count_; }
  size_t best_bytes() const { return best_bytes_; }
  Model take_best() { return std::move(best_); }

 private:
  const Model& base_;
  const std::vector<std::vector<float>>& frames_;
  const std::vector<int32_t>& rounded_;
  const FastLayerOptions& options_;
  const GridComponents pca_;
  Model best_, trial_;
  size_t best_bytes_ = SIZE_MAX;
  uint32_t best_count_ = 0;
};

// The counts of kCounts below the most the frames have, then that most, tried by slot: every
// other one, the last, then the two beside the best.
class CountLadder {
 public:
  explicit CountLadder(uint32_t most) {
    for (uint32_t K : kCounts)
      if (K < most) counts_.push_back(K);
    counts_.push_back(most);
    tried_.assign(counts_.size(), 0);
  }
  bool search(CountSearch* trials, std::string* error) {
    for (size_t i = 0; i < counts_.size(); i += 2)
      if (!run(i, trials, error)) return false;
    if (!run(counts_.size() - 1, trials, error)) return false;
    const size_t centre = best_;
    coded_ = true;  // a count past the format's ranges stops the larger ones only
    return (centre == 0 || run(centre - 1, trials, error)) && run(centre + 1, trials, error);
  }

 private:
  // Slot i's count, unless tried already or past a count the format could not hold.
  bool run(size_t i, CountSearch* trials, std::string* error) {
    if (i >= counts_.size() || tried_[i] || !coded_) return true;
    tried_[i] = 1;
    bool smaller = false;
    if (!trials->try_count(counts_[i], kBasisStep, &smaller, &coded_, error)) return false;
    if (smaller) best_ = i;
    return true;
  }
  std::vector<uint32_t> counts_;
  std::vector<uint8_t> tried_;
  size_t best_ = 0;
  bool coded_ = true;
};
}  // namespace

bool choose_fast_low_rank(Model* m, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
                          const FastLayerOptions& options, std::string* error, size_t* bytes) {
  Model base = *m;
  base.low_rank = LowRankModel();
  CountSearch search(base, frames, rounded, options);
  bool smaller = false, coded = true;
  if (options.components < 0) {
    CountLadder ladder(search.max_count());
    if (!ladder.search(&search, error)) return false;
  } else {
    const uint32_t K = std::min<uint32_t>(uint32_t(options.components), search.max_count());
    if (!search.try_count(K, kBasisStep, &smaller, &coded, error)) return false;
    // A count the format cannot hold gives the file without a model.
    if (!coded && !search.try_count(0, kBasisStep, &smaller, &coded, error)) return false;
  }
  if (search.best_bytes() == SIZE_MAX) return fail(error, "internal error: no low-rank trial could be coded");
  const uint32_t K = search.best_count();
  for (double step = kBasisStep * kStepRatio; K > 0 && step <= kMaxBasisStep; step *= kStepRatio) {
    if (!search.try_count(K, step, &smaller, &coded, error)) return false;
    if (!smaller) break;
  }
  if (bytes) *bytes = search.best_bytes();
  *m = search.take_best();
  return true;
}

}  // namespace dcurve
