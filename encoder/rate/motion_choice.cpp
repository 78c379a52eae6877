#include "encoder/rate/motion_choice.h"

#include <algorithm>
#include <cmath>

#include "codec/common/error.h"
#include "codec/compress/residual_encoder.h"
#include "encoder/rate/motion_costs.h"

namespace dcurve {
namespace {

// Residual bits motion (s, c, a) saves against the baseline: on the values of its curve
// and segment whose predictor is the Model (a shared boundary frame belongs to the later
// segment, as in the decoder).
double motion_saving(const Model& model, size_t s, uint32_t c, int a, const ValueCosts& with,
                     const ValueCosts& without) {
  const uint32_t V = model.meta.vertex_count;
  const auto [first, last] = predicted_frames(model, s);
  double saved = 0;
  for (uint32_t f = first; f <= last; ++f)
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

bool choose_motions(Model* model, const Model& baseline, const CodedPayload& baseline_coded, const EncodeContext& context,
                    const MotionChoiceOptions& options, MotionChoiceReport* report, std::string* error,
                    CodedResidual* coded) {
  MotionChoiceReport rep;
  rep.fitted = count_motions(*model);
  ValueCosts without;
  double compression = 1;
  if (!options.keep_all) {
    if (baseline.residual.step != model->residual.step || baseline.meta.frame_count != model->meta.frame_count ||
        baseline.meta.vertex_count != model->meta.vertex_count)
      return fail(error, "internal error: the baseline encode is on another grid");
    if (!coded_value_costs(baseline, baseline_coded, &without, error)) return false;
    compression = segs_compression(*model);
  }
  for (;;) {
    std::vector<int32_t> prediction, q = context.rounded;
    if (!stored_model_prediction(*model, &prediction, error)) return false;
    if (prediction.empty()) break;  // nothing left to plan with: the baseline stands
    ResidualOptions ro;
    ro.model_prediction = &prediction;
    ResidualPlan plan = choose_chunked_plan(*model, context.frames, context.snap_distance, &q, ro, context.plan);
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
    model->residual.payload = encode_residuals(*model, q, plan, ro);
    if (model->residual.payload.empty()) return fail(error, "internal error: the residual plan is invalid");
    if (coded) *coded = {{std::move(plan), std::move(q)}, std::move(prediction), {}};
    break;
  }
  rep.kept = count_motions(*model);
  if (report) *report = rep;
  return true;
}

}  // namespace dcurve
