#include "encoder/rate/inbetween_choice.h"

#include <algorithm>
#include <cstdint>
#include <map>
#include <memory>

#include "codec/common/error.h"
#include "codec/common/frame_evaluator.h"
#include "codec/common/inbetween.h"

namespace dcurve {
namespace {

// The corrections of one segment's even-offset frames, computed when a held-out frame
// first needs them (the model evaluated at each frame once).
class HalfRateCorrections {
 public:
  HalfRateCorrections(const FrameEvaluator& evaluator, const std::vector<std::vector<float>>& frames,
                      uint32_t first)
      : evaluator_(evaluator), frames_(frames), first_(first) {}

  // Correction of half-rate frame k (input frame first + 2k), evaluated in segment `place`.
  const std::vector<float>& at(uint32_t k, const FrameEvaluator::Place& segment) {
    auto it = cache_.find(k);
    if (it != cache_.end()) return it->second;
    if (cache_.size() > 8) cache_.erase(cache_.begin());  // keys rise: the oldest is least needed
    const uint32_t f = first_ + 2 * k;
    std::vector<float> d(frames_[f].size());
    FrameEvaluator::Place place = segment;
    place.i = f;
    place.w = 0.f;
    place.tau = model_tau(segment, f);
    evaluator_.model_at(place, d.data());
    for (size_t j = 0; j < d.size(); ++j) d[j] = frames_[f][j] - d[j];
    return cache_.emplace(k, std::move(d)).first->second;
  }

 private:
  double model_tau(const FrameEvaluator::Place& segment, uint32_t f) const {
    const uint32_t a = evaluator_.span_first(segment), b = evaluator_.span_last(segment);
    return b > a ? double(f - a) / double(b - a) : 0.0;
  }

  const FrameEvaluator& evaluator_;
  const std::vector<std::vector<float>>& frames_;
  uint32_t first_;
  std::map<uint32_t, std::vector<float>> cache_;
};

// Adds each rule's squared error at held-out frame f (odd offset from the segment's first
// frame, inside it) to scores.
void score_frame(const FrameEvaluator& evaluator, const std::vector<std::vector<float>>& frames, uint32_t f,
                 HalfRateCorrections* half, InbetweenScores* scores) {
  const FrameEvaluator::Place place = evaluator.locate(double(f));
  const uint32_t first = evaluator.span_first(place), last = evaluator.span_last(place);
  const uint32_t j = (f - first) / 2, n = (last - first) / 2;  // half-rate frames 0..n
  std::vector<float> model(frames[f].size());
  evaluator.model_at(place, model.data());
  for (uint8_t r = 0; r < kInbetweenCount; ++r) {
    double weight[kInbetweenStencil];
    inbetween_weights(Inbetween(r), 0, n, j, 0.5, weight);
    std::vector<double> predicted(model.begin(), model.end());
    for (int k = 0; k < kInbetweenStencil; ++k) {
      if (weight[k] == 0.0) continue;
      const std::vector<float>& d = half->at(uint32_t(int(j) + kInbetweenStencilFirst + k), place);
      for (size_t i = 0; i < d.size(); ++i) predicted[i] += weight[k] * double(d[i]);
    }
    double sum = 0;
    for (size_t i = 0; i < predicted.size(); ++i) {
      const double e = predicted[i] - double(frames[f][i]);
      sum += e * e;
    }
    scores->squared_error[r] += sum;
  }
  ++scores->held_out_frames;
}

}  // namespace

bool score_inbetweens(const Model& model, const std::vector<std::vector<float>>& frames, InbetweenScores* scores,
                      std::string* error) {
  *scores = InbetweenScores{};
  FrameEvaluator evaluator;
  if (!evaluator.build(model, UINT64_MAX, error)) return false;
  const uint32_t F = uint32_t(frames.size());
  uint32_t segment_first = UINT32_MAX;
  std::unique_ptr<HalfRateCorrections> half;
  for (uint32_t f = 1; f + 1 < F; ++f) {
    const FrameEvaluator::Place place = evaluator.locate(double(f));
    const uint32_t first = evaluator.span_first(place), last = evaluator.span_last(place);
    // A held-out frame needs half-rate frames on both sides inside its segment.
    if ((f - first) % 2 == 0 || f + 1 > first + 2 * ((last - first) / 2)) continue;
    if (first != segment_first) {
      half = std::make_unique<HalfRateCorrections>(evaluator, frames, first);
      segment_first = first;
    }
    score_frame(evaluator, frames, f, half.get(), scores);
  }
  return true;
}

bool choose_inbetween(Model* model, const std::vector<std::vector<float>>& frames, int forced, std::string* error) {
  if (forced >= 0 && forced < int(kInbetweenCount)) {
    model->meta.inbetween = Inbetween(forced);
    return true;
  }
  InbetweenScores scores;
  if (!score_inbetweens(*model, frames, &scores, error)) return false;
  uint8_t best = 0;
  for (uint8_t r = 1; r < kInbetweenCount; ++r)
    if (scores.squared_error[r] < scores.squared_error[best]) best = r;
  model->meta.inbetween = Inbetween(best);
  return true;
}

}  // namespace dcurve
