#include "codec/decompress/model_prediction.h"

#include <algorithm>
#include <cmath>

#include "codec/common/error.h"
#include "codec/common/low_rank.h"
#include "codec/decompress/residual_decoder.h"

namespace dcurve {
namespace {

// The mean and basis vectors are K + 1 pseudo-frames of the same mesh, coded by the
// residual coder (its spatial predictors suit smooth basis shapes).
bool decode_low_rank_basis(const Model& model, uint64_t max_values, const ResidualOptions& options,
                           std::vector<int32_t>* out, std::string* error) {
  const LowRankModel& lr = model.low_rank;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  if ((uint64_t(lr.components) + 1) * n > max_values)
    return fail(error, "low-rank model is implausibly large for the file size");
  const Model pseudo = low_rank_basis_model(model);
  ResidualOptions basis_options = options;
  basis_options.low_rank_basis = true;
  std::string why;
  if (!decode_residuals(pseudo, out, &why, basis_options)) return fail(error, "low-rank basis: " + why);
  for (size_t i = n; i < out->size(); ++i)
    if ((*out)[i] < -kMaxLowRankBasis || (*out)[i] > kMaxLowRankBasis)
      return fail(error, "low-rank basis value out of range");
  return true;
}

}  // namespace

Model low_rank_basis_model(const Model& model) {
  Model pseudo;
  pseudo.meta = model.meta;
  pseudo.meta.frame_count = model.low_rank.components + 1;
  pseudo.faces = model.faces;
  pseudo.curves = model.curves;
  pseudo.residual.payload = model.low_rank.basis_payload;
  return pseudo;
}

bool has_motion_model(const Model& model) {
  for (const Segment& s : model.segments)
    for (const CurveMotion& m : s.motion)
      if (m.basis != Basis::Zero) return true;
  return false;
}

bool has_model_prediction(const Model& model) { return model.low_rank.components > 0 || has_motion_model(model); }

bool GridPredictor::build(const Model& model, uint64_t max_values, std::string* error, const Traversal* traversal,
                          const FastTraversal* fast_traversal) {
  model_ = &model;
  active_ = has_model_prediction(model);
  if (!evaluator_.build(model, max_values, error)) return false;
  if (model.low_rank.components == 0) return true;
  std::vector<int32_t> mean_and_basis;
  ResidualOptions options;  // the file's traversals: same vertices, faces and curves
  options.traversal = traversal;
  options.fast_traversal = fast_traversal;
  if (!decode_low_rank_basis(model, max_values, options, &mean_and_basis, error)) return false;
  low_rank_.assign(mean_and_basis, size_t(model.meta.vertex_count) * 3);
  return true;
}

void GridPredictor::frame(uint32_t f, int32_t* out, PredictionScratch* scratch) const {
  const Model& m = *model_;
  const size_t n = size_t(m.meta.vertex_count) * 3;
  if (m.low_rank.components > 0) {
    low_rank_frame(m.low_rank, f, low_rank_, n, out);
    return;
  }
  scratch->xyz.resize(n);
  const float* xyz = scratch->xyz.data();
  evaluator_.model_at(evaluator_.locate(double(f)), scratch->xyz.data());
  // Far outside any sane grid; keeps the residual arithmetic inside int64 on hostile files.
  constexpr double kLimit = double(1 << 30);
  const ResidualLayer& grid = m.residual;
  for (size_t i = 0; i < n; ++i) {
    const double g = std::nearbyint((double(xyz[i]) - grid.origin[i % 3]) / grid.step);
    out[i] = int32_t(std::clamp(std::isfinite(g) ? g : 0.0, -kLimit, kLimit));
  }
}

bool model_grid_prediction(const Model& model, uint64_t max_values, std::vector<int32_t>* out, std::string* error) {
  GridPredictor predictor;
  if (!predictor.build(model, max_values, error)) return false;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  if (uint64_t(model.meta.frame_count) * n > max_values)
    return fail(error, "model prediction is implausibly large for the file size");
  out->resize(n * model.meta.frame_count);
  PredictionScratch scratch;
  for (uint32_t f = 0; f < model.meta.frame_count; ++f) predictor.frame(f, out->data() + f * n, &scratch);
  return true;
}

}  // namespace dcurve
