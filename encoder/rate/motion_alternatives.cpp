#include "encoder/rate/motion_alternatives.h"

#include <algorithm>
#include <cmath>

#include "codec/common/error.h"
#include "codec/common/predictors.h"
#include "encoder/rate/motion_costs.h"

namespace dcurve {
namespace {

// A slot is promising when its estimate is at most this times the baseline's bytes: the
// estimate ignores snapping and the other spatial corrections, which can only help the
// Model predictor, though it also ignores that clusters rarely follow one curve. The
// margin above 1 allows for that slack; a slot estimated well above its baseline is not
// kept by the full plan (and even one estimated far below may not be).
constexpr double kPromisingFactor = 1.25;

struct Pricing {
  const Model& model;
  const ValueCosts& costs;  // the baseline's
  const Traversal& trav;
  const std::vector<uint32_t>& position;  // traversal position of each vertex
  const std::vector<int32_t>& rounded;
};

// Estimated bytes of every motion slot of `segments` (index (s * C + c) * 3 + axis): SEGS
// bytes plus residual bytes under the Model predictor; HUGE_VAL for Zero motions.
bool slot_estimates(const Pricing& p, const std::vector<Segment>& segments, std::vector<double>* out,
                    std::string* error) {
  Model trial = p.model;
  trial.segments = segments;
  const uint32_t C = trial.curves.curve_count(), V = trial.meta.vertex_count;
  const size_t n = size_t(V) * 3;
  out->assign(segments.size() * C * 3, HUGE_VAL);
  std::vector<int32_t> prediction;
  if (!stored_model_prediction(trial, &prediction, error)) return false;
  if (prediction.empty()) return true;
  const double compression = segs_compression(trial);
  std::vector<int64_t> err(n);
  std::vector<double> off(size_t(C) * 3), mean(size_t(C) * 3);
  for (size_t s = 0; s < segments.size(); ++s) {
    double* slot = out->data() + s * C * 3;
    for (size_t k = 0; k < size_t(C) * 3; ++k)
      if (segments[s].motion[k].basis != Basis::Zero) slot[k] = motion_record_bytes(segments[s].motion[k]) * compression;
    const auto [first, last] = predicted_frames(trial, s);
    for (uint32_t f = first; f <= last; ++f) {
      for (size_t i = 0; i < n; ++i) err[i] = int64_t(prediction[f * n + i]) - p.rounded[f * n + i];
      for (uint32_t c = 0; c < C; ++c)
        for (int a = 0; a < 3; ++a) {
          double bits_off = 0, bits_mean = 0;
          for (uint32_t i = trial.curves.offsets[c]; i < trial.curves.offsets[c + 1]; ++i) {
            const uint32_t v = trial.curves.vertices[i], pos = p.position[v];
            const int64_t e = err[size_t(v) * 3 + size_t(a)];
            int64_t sum = 0;
            const uint32_t nb_begin = p.trav.nb_offsets[pos], nb_end = p.trav.nb_offsets[pos + 1];
            for (uint32_t k = nb_begin; k < nb_end; ++k) sum += err[size_t(p.trav.nb[k]) * 3 + size_t(a)];
            const int64_t correction = nb_end > nb_begin ? detail::rounded_mean(sum, nb_end - nb_begin) : 0;
            bits_off += p.costs.residual_bits(e);
            bits_mean += p.costs.residual_bits(e - correction);
          }
          slot[size_t(c) * 3 + size_t(a)] += std::min(bits_off, bits_mean) / 8;
        }
    }
  }
  return true;
}

// The baseline's residual bytes of every motion slot's values under segments' bounds.
std::vector<double> baseline_slots(const Pricing& p, const std::vector<Segment>& segments) {
  Model trial = p.model;
  trial.segments = segments;
  const uint32_t C = trial.curves.curve_count(), V = trial.meta.vertex_count;
  std::vector<double> out(segments.size() * C * 3, 0.0);
  for (size_t s = 0; s < segments.size(); ++s) {
    const auto [first, last] = predicted_frames(trial, s);
    for (uint32_t f = first; f <= last; ++f)
      for (uint32_t c = 0; c < C; ++c)
        for (uint32_t i = trial.curves.offsets[c]; i < trial.curves.offsets[c + 1]; ++i)
          for (int a = 0; a < 3; ++a)
            out[(s * C + c) * 3 + size_t(a)] +=
                double(p.costs.bits[(size_t(f) * V + trial.curves.vertices[i]) * 3 + size_t(a)]) / 8;
  }
  return out;
}

bool same_bounds(const std::vector<Segment>& a, const std::vector<Segment>& b) {
  if (a.size() != b.size()) return false;
  for (size_t s = 0; s < a.size(); ++s)
    if (a[s].first_frame != b[s].first_frame || a[s].last_frame != b[s].last_frame) return false;
  return true;
}

}  // namespace

bool choose_motion_alternative(const Model& model, const Model& baseline, const CodedPayload& baseline_coded,
                               const std::vector<std::vector<Segment>>& fitted, const std::vector<int32_t>& rounded,
                               std::vector<Segment>* chosen, MotionAlternativesReport* report, std::string* error) {
  if (fitted.empty()) return fail(error, "internal error: no fitted motion model to choose from");
  ValueCosts costs;
  if (!coded_value_costs(baseline, baseline_coded, &costs, error)) return false;
  if (costs.bits.size() != rounded.size()) return fail(error, "internal error: the baseline encode is on another grid");
  const Traversal trav = build_traversal(model);
  std::vector<uint32_t> position(model.meta.vertex_count);
  for (uint32_t i = 0; i < trav.order.size(); ++i) position[trav.order[i]] = i;
  const Pricing pricing{model, costs, trav, position, rounded};

  std::vector<std::vector<double>> estimates(fitted.size());
  for (size_t k = 0; k < fitted.size(); ++k)
    if (!slot_estimates(pricing, fitted[k], &estimates[k], error)) return false;
  MotionAlternativesReport best;
  best.estimated_bytes = HUGE_VAL;
  std::vector<uint8_t> grouped(fitted.size(), 0);
  for (size_t g = 0; g < fitted.size(); ++g) {
    if (grouped[g]) continue;
    std::vector<size_t> members;
    for (size_t k = g; k < fitted.size(); ++k)
      if (!grouped[k] && same_bounds(fitted[g], fitted[k])) {
        grouped[k] = 1;
        members.push_back(k);
      }
    const std::vector<double> plain = baseline_slots(pricing, fitted[g]);
    std::vector<Segment> mix = fitted[g];
    const uint32_t C = model.curves.curve_count();
    double total = 0, plain_total = 0;
    uint32_t motions = 0, promising = 0;
    for (size_t slot = 0; slot < plain.size(); ++slot) {
      size_t pick = members[0];
      for (size_t k : members)
        if (estimates[k][slot] < estimates[pick][slot]) pick = k;
      mix[slot / (size_t(C) * 3)].motion[slot % (size_t(C) * 3)] = fitted[pick][slot / (size_t(C) * 3)].motion[slot % (size_t(C) * 3)];
      total += std::min(estimates[pick][slot], plain[slot]);
      plain_total += plain[slot];
      motions += estimates[pick][slot] < HUGE_VAL;
      promising += estimates[pick][slot] <= kPromisingFactor * plain[slot];
    }
    if (total < best.estimated_bytes) {
      best = {g, total, plain_total, motions, promising};
      *chosen = std::move(mix);
    }
  }
  if (report) *report = best;
  return true;
}

}  // namespace dcurve
