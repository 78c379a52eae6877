#include "encoder/rate/motion_choice.h"

#include <algorithm>
#include <cmath>

#include "codec/bytes.h"
#include "codec/container.h"
#include "codec/error.h"
#include "decoder/model_prediction.h"

namespace dcurve {
namespace {

constexpr int kClasses = 2 * 41 + 1;

int exponent_class(int64_t r, int* exponent) {
  *exponent = 0;
  if (r == 0) return 0;
  uint64_t m = r < 0 ? uint64_t(-r) : uint64_t(r);
  int e = 0;
  while (m >>= 1) ++e;
  e = std::min(e, 40);
  *exponent = e;
  return 1 + 2 * e + (r < 0);
}

// What coding each grid value costs under `plan`, and whether its predictor is the Model.
struct ValueCosts {
  std::vector<float> bits;       // (f * V + v) * 3 + axis
  std::vector<uint8_t> by_model; // same index; 1 when the value's predictor kind is Model
};

// Per-value bits: the order-0 entropy of the value's exponent class over the whole stream
// plus its mantissa bits. The coder's contexts are ignored, so only differences between
// two plans of the same frames mean something.
bool value_costs(const Model& model, const std::vector<int32_t>& q, const PredictorPlan& plan,
                 const ResidualOptions& ro, ValueCosts* out, std::string* error) {
  const uint32_t V = model.meta.vertex_count;
  const size_t n = size_t(V) * 3;
  const std::vector<int64_t> r = residual_values(model, q, plan, ro);
  if (r.size() != n * plan.order.size() || plan.frames.size() != model.meta.frame_count)
    return fail(error, "internal error: residual values do not match the plan");
  std::vector<double> hist(kClasses, 0.0);
  for (int64_t x : r) {
    int e;
    hist[size_t(exponent_class(x, &e))] += 1;
  }
  std::vector<double> class_bits(kClasses, 0.0);
  for (int k = 0; k < kClasses; ++k)
    if (hist[size_t(k)] > 0) class_bits[size_t(k)] = -std::log2(hist[size_t(k)] / double(r.size()));
  const Traversal trav = build_traversal(model);
  out->bits.assign(q.size(), 0.f);
  out->by_model.assign(q.size(), 0);
  for (size_t k = 0; k < plan.order.size(); ++k) {
    const uint32_t f = plan.order[k];
    const FramePredictors& fp = plan.frames[f];
    for (uint32_t pos = 0; pos < V; ++pos) {
      const uint32_t cluster = pos / std::max(plan.cluster_size, 1u);
      const size_t j = fp.cluster_candidate.empty() ? 0 : fp.cluster_candidate[cluster];
      const size_t at = (size_t(f) * V + trav.order[pos]) * 3;
      for (int a = 0; a < 3; ++a) {
        int e;
        const int64_t x = r[k * n + size_t(pos) * 3 + size_t(a)];
        out->bits[at + size_t(a)] = float(class_bits[size_t(exponent_class(x, &e))] + e);
        out->by_model[at + size_t(a)] = fp.candidates[j][size_t(a)].kind == PredictorKind::Model;
      }
    }
  }
  return true;
}

// Bytes the SEGS section stores for `m` beyond a Zero motion's single byte.
double motion_record_bytes(const CurveMotion& m) {
  if (m.basis == Basis::Zero) return 0;
  double bytes = 1 + 4 + 4 + 1;  // basis_case, time_param, space_param, coeff_exponent
  for (float c : m.coeffs) {
    uint64_t z = zigzag_encode(int64_t(std::ldexp(double(c), -m.coeff_exponent)));
    do {
      ++bytes;
      z >>= 7;
    } while (z);
  }
  return bytes;
}

// SEGS stored bytes per raw byte as zstd leaves them for this model (1 when uncompressed).
double segs_compression(const Model& model, std::string* error) {
  const std::vector<uint8_t> bytes = write_container(model);
  Model back;
  std::vector<SectionInfo> sections;
  if (!read_container(bytes.data(), bytes.size(), &back, error, &sections)) return -1;
  for (const SectionInfo& s : sections)
    if (s.tag == "SEGS" && s.raw_bytes > 0) return double(s.stored_bytes) / double(s.raw_bytes);
  return 1;
}

// The costs of `baseline`'s own coded residuals (its low-rank prediction included).
bool baseline_costs(const Model& baseline, ValueCosts* out, std::string* error) {
  std::vector<int32_t> prediction, q;
  ResidualOptions ro;
  if (has_model_prediction(baseline)) {
    if (!model_grid_prediction(baseline, UINT64_MAX, &prediction, error)) return false;
    ro.model_prediction = &prediction;
  }
  PredictorPlan plan;
  if (!decode_residuals(baseline, &q, error, ro) || !decode_predictor_plan(baseline, &plan, error, ro, true))
    return false;
  return value_costs(baseline, q, plan, ro, out, error);
}

// Residual bits motion (s, c, a) saves against the baseline: on the values of its curve
// and segment whose predictor is the Model (a shared boundary frame belongs to the later
// segment, as in the decoder).
double motion_saving(const Model& model, size_t s, uint32_t c, int a, const ValueCosts& with,
                     const ValueCosts& without) {
  const Segment& seg = model.segments[s];
  const uint32_t V = model.meta.vertex_count;
  const uint32_t last = s + 1 < model.segments.size() && seg.last_frame > seg.first_frame ? seg.last_frame - 1
                                                                                           : seg.last_frame;
  double saved = 0;
  for (uint32_t f = seg.first_frame; f <= last; ++f)
    for (uint32_t i = model.curves.offsets[c]; i < model.curves.offsets[c + 1]; ++i) {
      const size_t at = (size_t(f) * V + model.curves.vertices[i]) * 3 + size_t(a);
      if (with.by_model[at]) saved += double(without.bits[at]) - double(with.bits[at]);
    }
  return saved / 8;
}

uint32_t count_motions(const Model& model) {
  uint32_t n = 0;
  for (const Segment& s : model.segments)
    for (const CurveMotion& m : s.motion) n += m.basis != Basis::Zero;
  return n;
}

}  // namespace

bool stored_model_prediction(const Model& model, std::vector<int32_t>* prediction, std::string* error) {
  prediction->clear();
  if (!has_model_prediction(model)) return true;
  const std::vector<uint8_t> bytes = write_container(model);
  Model stored;
  if (!read_container(bytes.data(), bytes.size(), &stored, error)) return false;
  return model_grid_prediction(stored, UINT64_MAX, prediction, error);
}

bool choose_motions(Model* model, const Model& baseline, const std::vector<std::vector<float>>& frames,
                    const std::vector<int32_t>& rounded, double snap_distance,
                    const ResidualPlanOptions& plan_options, const MotionChoiceOptions& options,
                    MotionChoiceReport* report, std::string* error) {
  MotionChoiceReport rep;
  rep.fitted = count_motions(*model);
  ValueCosts without;
  double compression = 1;
  if (!options.keep_all) {
    if (baseline.residual.step != model->residual.step || baseline.meta.frame_count != model->meta.frame_count ||
        baseline.meta.vertex_count != model->meta.vertex_count)
      return fail(error, "internal error: the baseline encode is on another grid");
    if (!baseline_costs(baseline, &without, error)) return false;
    compression = segs_compression(*model, error);
    if (compression < 0) return false;
  }
  for (;;) {
    std::vector<int32_t> prediction, q = rounded;
    if (!stored_model_prediction(*model, &prediction, error)) return false;
    if (prediction.empty()) break;  // nothing left to plan with: the baseline stands
    ResidualOptions ro;
    ro.model_prediction = &prediction;
    const PredictorPlan plan = choose_plan_and_grid(*model, frames, snap_distance, &q, ro, plan_options);
    ++rep.plans;
    bool dropped = false;
    if (!options.keep_all && rep.plans <= options.max_screens) {
      ValueCosts with;
      if (!value_costs(*model, q, plan, ro, &with, error)) return false;
      rep.estimated_saving = 0;
      for (size_t s = 0; s < model->segments.size(); ++s)
        for (uint32_t c = 0; c < model->curves.curve_count(); ++c)
          for (int a = 0; a < 3; ++a) {
            CurveMotion& m = model->segments[s].motion[size_t(c) * 3 + size_t(a)];
            if (m.basis == Basis::Zero) continue;
            const double saved = motion_saving(*model, s, c, a, with, without);
            if (saved > motion_record_bytes(m) * compression) {
              rep.estimated_saving += saved;
              continue;
            }
            m = CurveMotion();
            dropped = true;
          }
    }
    // A plan made with motions since dropped predicts from values the file no longer has:
    // only a plan that dropped nothing codes the payload.
    if (dropped) continue;
    model->residual.payload = encode_residuals(*model, q, &plan, ro);
    if (model->residual.payload.empty()) return fail(error, "internal error: the residual plan is invalid");
    break;
  }
  rep.kept = count_motions(*model);
  if (report) *report = rep;
  return true;
}

}  // namespace dcurve
