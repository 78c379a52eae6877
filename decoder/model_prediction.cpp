#include "model_prediction.h"

#include <algorithm>
#include <cmath>

#include "codec/error.h"
#include "codec/low_rank.h"
#include "codec/residual.h"
#include "frame_evaluator.h"

namespace dcurve {
namespace {

bool pde_grid_prediction(const Model& model, uint64_t max_floats, std::vector<int32_t>* out, std::string* error) {
  FrameEvaluator model_only;
  if (!model_only.build(model, {}, max_floats, error)) return false;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  const ResidualLayer& grid = model.residual;
  out->resize(n * model.meta.frame_count);
  std::vector<float> xyz(n);
  // Far outside any sane grid; keeps the residual arithmetic inside int64 on hostile files.
  constexpr double kLimit = double(1 << 30);
  for (uint32_t f = 0; f < model.meta.frame_count; ++f) {
    model_only.evaluate(double(f), xyz.data());
    int32_t* qf = out->data() + f * n;
    for (size_t i = 0; i < n; ++i) {
      double g = std::nearbyint((double(xyz[i]) - grid.origin[i % 3]) / grid.step);
      qf[i] = int32_t(std::clamp(std::isfinite(g) ? g : 0.0, -kLimit, kLimit));
    }
  }
  return true;
}

bool low_rank_grid_prediction(const Model& model, uint64_t max_values, std::vector<int32_t>* out,
                              std::string* error) {
  const LowRankModel& lr = model.low_rank;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  if ((uint64_t(lr.components) + 1 + model.meta.frame_count) * n > max_values)
    return fail(error, "low-rank model is implausibly large for the file size");
  // The mean and basis vectors are K + 1 pseudo-frames of the same mesh, coded by the
  // residual coder (its spatial predictors suit smooth basis shapes).
  Model pseudo;
  pseudo.meta = model.meta;
  pseudo.meta.frame_count = lr.components + 1;
  pseudo.faces = model.faces;
  pseudo.curves = model.curves;
  pseudo.residual.payload = lr.basis_payload;
  std::vector<int32_t> mean_and_basis;
  std::string why;
  if (!decode_residuals(pseudo, &mean_and_basis, &why)) return fail(error, "low-rank basis: " + why);
  for (size_t i = n; i < mean_and_basis.size(); ++i)
    if (mean_and_basis[i] < -kMaxLowRankBasis || mean_and_basis[i] > kMaxLowRankBasis)
      return fail(error, "low-rank basis value out of range");
  out->resize(n * model.meta.frame_count);
  for (uint32_t f = 0; f < model.meta.frame_count; ++f)
    low_rank_frame(lr, f, mean_and_basis.data(), n, out->data() + f * n);
  return true;
}

}  // namespace

bool has_motion_model(const Model& model) {
  for (const Segment& s : model.segments)
    for (const CurveMotion& m : s.motion)
      if (m.basis != Basis::Zero) return true;
  return false;
}

bool has_model_prediction(const Model& model) { return model.low_rank.components > 0 || has_motion_model(model); }

bool model_grid_prediction(const Model& model, uint64_t max_floats, std::vector<int32_t>* out, std::string* error) {
  if (model.low_rank.components > 0) return low_rank_grid_prediction(model, max_floats, out, error);
  return pde_grid_prediction(model, max_floats, out, error);
}

}  // namespace dcurve
