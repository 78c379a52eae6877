#include "encoder/rate/motion_costs.h"

#include <algorithm>
#include <cmath>

#include "codec/common/error.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/quantize.h"
#include "codec/compress/residual_encoder.h"
#include "codec/compress/residual_values.h"
#include "codec/decompress/model_prediction.h"
#include "encoder/rate/plan_steps.h"

namespace dcurve {

double ValueCosts::residual_bits(int64_t r) const {
  int e;
  const int k = residual_class(r, &e);
  return class_bits[size_t(k)] + e;
}

bool value_costs(const Model& model, const std::vector<int32_t>& q, const ResidualPlan& plan,
                 const ResidualOptions& ro, ValueCosts* out, std::string* error) {
  const uint32_t V = model.meta.vertex_count;
  const size_t n = size_t(V) * 3;
  const std::vector<int64_t> r = residual_values(model, q, plan, ro);
  const std::vector<CodedFrame> coded = coded_frames(plan);
  if (r.size() != n * coded.size() || coded.size() != model.meta.frame_count)
    return fail(error, "internal error: residual values do not match the plan");
  std::vector<double> hist(kResidualClasses, 0.0);
  for (int64_t x : r) {
    int e;
    hist[size_t(residual_class(x, &e))] += 1;
  }
  // Half a count for classes never seen: other predictions of the same values may use them.
  out->class_bits.assign(kResidualClasses, 0.0);
  for (int k = 0; k < kResidualClasses; ++k)
    out->class_bits[size_t(k)] = -std::log2((hist[size_t(k)] + 0.5) / (double(r.size()) + 0.5 * kResidualClasses));
  const Traversal trav = build_traversal(model);
  out->bits.assign(q.size(), 0.f);
  out->by_model.assign(q.size(), 0);
  for (size_t k = 0; k < coded.size(); ++k) {
    const uint32_t f = coded[k].frame;
    const FramePredictors& fp = *coded[k].predictors;
    for (uint32_t pos = 0; pos < V; ++pos) {
      const uint32_t cluster = pos / std::max(coded[k].chunk->cluster_size, 1u);
      const size_t j = fp.cluster_candidate.empty() ? 0 : fp.cluster_candidate[cluster];
      const size_t at = (size_t(f) * V + trav.order[pos]) * 3;
      for (int a = 0; a < 3; ++a) {
        out->bits[at + size_t(a)] = float(out->residual_bits(r[k * n + size_t(pos) * 3 + size_t(a)]));
        out->by_model[at + size_t(a)] = fp.candidates[j][size_t(a)].kind == PredictorKind::Model;
      }
    }
  }
  return true;
}

double motion_record_bytes(const CurveMotion& m) {
  return m.basis == Basis::Zero ? 0 : double(motion_record_size(m) - 1);
}

namespace {
// What write_container can write: a residual layer whose payload is not coded yet gets one
// of zeros (the round trips below read the other sections back).
std::vector<uint8_t> written(const Model& model, std::vector<SectionInfo>* sections = nullptr) {
  if (!(model.residual.step > 0) || !model.residual.payload.empty()) return write_container(model, {}, sections);
  Model m = model;
  m.residual.payload = encode_residuals(m, std::vector<int32_t>(size_t(m.meta.vertex_count) * 3 * m.meta.frame_count, 0));
  return write_container(m, {}, sections);
}
}  // namespace

double segs_compression(const Model& model) {
  std::vector<SectionInfo> sections;
  written(model, &sections);
  for (const SectionInfo& s : sections)
    if (s.tag == "SEGS" && s.raw_bytes > 0) return double(s.stored_bytes) / double(s.raw_bytes);
  return 1;
}

bool coded_value_costs(const Model& baseline, const CodedPayload& coded, ValueCosts* out, std::string* error) {
  if (has_model_prediction(baseline)) return fail(error, "internal error: the baseline encode has a Model prediction");
  return value_costs(baseline, coded.values, coded.plan, {}, out, error);
}

std::pair<uint32_t, uint32_t> predicted_frames(const Model& model, size_t s) {
  const Segment& seg = model.segments[s];
  const bool shared = s + 1 < model.segments.size() && seg.last_frame > seg.first_frame;
  return {seg.first_frame, shared ? seg.last_frame - 1 : seg.last_frame};
}

bool stored_model_prediction(const Model& model, std::vector<int32_t>* prediction, std::string* error) {
  prediction->clear();
  if (!has_model_prediction(model)) return true;
  Model stored = model;
  for (float& u : stored.curves.u) u = quantize_curve_u(u);
  return model_grid_prediction(stored, UINT64_MAX, prediction, error);
}

}  // namespace dcurve
