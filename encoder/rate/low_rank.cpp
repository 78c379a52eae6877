#include "encoder/rate/low_rank.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "codec/common/low_rank.h"
#include "codec/common/residual.h"
#include "codec/common/fast_fit.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/compress/residual_encoder.h"
#include "encoder/parallel.h"

namespace dcurve {

GridComponents grid_components(const std::vector<int32_t>& q, uint32_t F, size_t n, uint32_t max_components,
                               uint32_t anchor) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor X(F, n);
  for (uint32_t f = 0; f < F; ++f)
    for (size_t i = 0; i < n; ++i) X(f, Eigen::Index(i)) = q[size_t(f) * n + i];
  GridComponents out;
  out.anchor = anchor < F ? anchor : kMeanAnchor;
  const Eigen::RowVectorXd mean =
      out.anchor == kMeanAnchor ? Eigen::RowVectorXd(X.colwise().mean()) : Eigen::RowVectorXd(X.row(out.anchor));
  out.mean.assign(mean.data(), mean.data() + n);
  X.rowwise() -= mean;
  // F is small next to 3V: the F x F Gram matrix has the same nonzero spectrum as X^T X.
  const Eigen::MatrixXd gram = X * X.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(gram);
  const Eigen::VectorXd lambda = eig.eigenvalues().reverse();
  const Eigen::MatrixXd U = eig.eigenvectors().rowwise().reverse();
  for (Eigen::Index k = 0; k < lambda.size() && uint32_t(k) < max_components; ++k) {
    if (!(lambda(k) > 1e-12 * std::max(lambda(0), 1e-300))) break;
    const Eigen::VectorXd w = U.col(k) * std::sqrt(double(F));
    const Eigen::VectorXd a = (X.transpose() * U.col(k)) / std::sqrt(double(F));
    out.weights.emplace_back(w.data(), w.data() + F);
    out.amplitudes.emplace_back(a.data(), a.data() + n);
  }
  return out;
}

namespace {

bool round_to(double x, int64_t limit, int32_t* out) {
  const double r = std::nearbyint(x);
  if (!(std::fabs(r) <= double(limit))) return false;
  *out = int32_t(r);
  return true;
}

// A basis vector's values may lie up to this far (basis steps, per value) from the exact
// amplitude instead of at the nearest integer: snapped towards their spatial prediction,
// they code smaller, and the residual layer corrects the larger basis error.
constexpr double kBasisSnap = 0.75;

// One basis vector's values qf (V * 3) chosen from its exact amplitudes x (basis steps):
// each the integer within kBasisSnap of its amplitude that lies nearest its prediction under
// `mode` (kind None; Geometric weights from `mean`, the mean's values), vertices in traversal
// order so every prediction sees the values chosen before it.
void snap_basis_vector(const Traversal& t, const double* x_all, const int32_t* mean, SpatialMode mode, int32_t* qf) {
  const PredictorChoice choice[3] = {{PredictorKind::None, 0, 0, mode, 0}, {PredictorKind::None, 0, 0, mode, 0},
                                     {PredictorKind::None, 0, 0, mode, 0}};
  const std::vector<int32_t> weights = spatial_weights(t, mean, mode);
  const int32_t* w[3] = {weights.data(), weights.data(), weights.data()};
  auto zero = [](uint32_t, int) { return int64_t(0); };
  for (uint32_t pos = 0; pos < t.order.size(); ++pos) {
    const size_t v = t.order[pos];
    int64_t pred[3];
    vertex_prediction(choice, t, pos, qf, zero, pred, w);
    for (int a = 0; a < 3; ++a) {
      const double x = x_all[v * 3 + size_t(a)];
      const double limit = double(kMaxLowRankBasis);
      const double lo = std::max(std::ceil(x - kBasisSnap), -limit), hi = std::min(std::floor(x + kBasisSnap), limit);
      qf[v * 3 + size_t(a)] = int32_t(std::clamp(double(pred[a]), lo, std::max(lo, hi)));
    }
  }
}

// Codes the K + 1 pseudo-frames with the residual coder, each from its own mesh neighbours
// (kind None) with the spatial mode that codes it smallest: the mean and the first
// components are smooth fields (Parallelogram or Mean wins), the last ones mostly noise
// that neighbours do not predict (Off wins). A mode per pseudo-frame instead of one for all,
// since the smooth and the noisy ones each code smaller under their own. A basis vector is
// a field over the mean shape, so Geometric takes its weights from the mean (g = 0).
// Basis values are snapped (snap_basis_vector) under each mode tried; `values` receives the
// ones coded. `exact`: the K basis vectors' amplitudes in basis steps. memo (may be null):
// the modes and values chosen for this mean and step by earlier calls, extended here.
// traversal (may be null): build_traversal of the model's faces or curves. plan_out (may be
// null) receives the plan coded.
std::vector<uint8_t> code_mean_and_basis(const Model& model, std::vector<int32_t>* values_io,
                                         const std::vector<double>& exact, uint32_t frames, int threads,
                                         BasisMemo::Entry* memo, const Traversal* traversal,
                                         PredictorPlan* plan_out = nullptr) {
  std::vector<int32_t>& values = *values_io;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  Model pseudo;
  pseudo.meta = model.meta;
  pseudo.faces = model.faces;
  pseudo.curves = model.curves;
  auto plan_of = [](const std::vector<SpatialMode>& modes) {
    std::vector<uint32_t> order(modes.size());
    std::vector<PredictorChoice> choices;
    for (uint32_t f = 0; f < modes.size(); ++f) {
      order[f] = f;
      choices.insert(choices.end(), 3, PredictorChoice{PredictorKind::None, 0, 0, modes[f], 0});
    }
    return uniform_plan(order, choices);
  };
  Traversal owned;
  const Traversal& trav = traversal ? *traversal : (owned = build_traversal(pseudo));
  ResidualOptions options;
  options.traversal = &trav;
  // The mode of the last of `trial`'s frames that codes `vals` (those frames) smallest; with
  // `snap` (that frame's exact amplitudes), the frame is snapped under each mode first and
  // `vals` keeps the best's values.
  auto smallest_mode = [&](std::vector<int32_t>* vals, std::vector<SpatialMode> trial, const double* snap) {
    Model m = pseudo;
    m.meta.frame_count = uint32_t(trial.size());
    size_t smallest = SIZE_MAX;
    SpatialMode best = SpatialMode::Off;
    std::vector<int32_t> best_vals;
    const size_t last = trial.size() - 1;
    for (uint8_t s = 0; s < kSpatialModeCount; ++s) {
      trial.back() = SpatialMode(s);
      if (snap) snap_basis_vector(trav, snap, vals->data(), SpatialMode(s), vals->data() + last * n);
      PredictorPlan plan = plan_of(trial);
      const size_t bytes = encode_residuals(m, *vals, &plan, options).size();
      if (bytes > 0 && bytes < smallest) {
        smallest = bytes;
        best = SpatialMode(s);
        if (snap) best_vals = *vals;
      }
    }
    if (snap && !best_vals.empty()) *vals = std::move(best_vals);
    return best;
  };
  std::vector<SpatialMode> modes(frames, SpatialMode::Off);
  std::vector<int32_t> mean(values.begin(), values.begin() + std::ptrdiff_t(n));
  // Components the memo holds are copied; the others are chosen and added to it.
  const size_t known = memo ? std::min<size_t>(memo->modes.size(), frames - 1) : 0;
  modes[0] = memo && !memo->modes.empty() ? memo->mean_mode : smallest_mode(&mean, {SpatialMode::Off}, nullptr);
  for (size_t k = 0; k < known; ++k) {
    modes[k + 1] = memo->modes[k];
    std::copy(memo->values.begin() + std::ptrdiff_t(k * n), memo->values.begin() + std::ptrdiff_t((k + 1) * n),
              values.begin() + std::ptrdiff_t((k + 1) * n));
  }
  parallel_for(frames - 1 - known, threads, [&](size_t i) {
    const size_t k = known + i;
    std::vector<int32_t> two = mean;  // the mean, then basis vector k
    two.insert(two.end(), values.begin() + std::ptrdiff_t((k + 1) * n), values.begin() + std::ptrdiff_t((k + 2) * n));
    modes[k + 1] = smallest_mode(&two, {modes[0], SpatialMode::Off}, exact.data() + k * n);
    std::copy(two.begin() + std::ptrdiff_t(n), two.end(), values.begin() + std::ptrdiff_t((k + 1) * n));
  });
  if (memo && frames - 1 > known) {
    memo->mean_mode = modes[0];
    memo->modes.assign(modes.begin() + 1, modes.end());
    memo->values.assign(values.begin() + std::ptrdiff_t(n), values.end());
  }
  pseudo.meta.frame_count = frames;
  PredictorPlan plan = plan_of(modes);
  std::vector<uint8_t> payload = encode_residuals(pseudo, values, &plan, options);
  if (plan_out) *plan_out = std::move(plan);
  return payload;
}

// One basis vector's values (plane, V * 3) chosen from its exact amplitudes x (basis steps)
// for the fast payload: each within kBasisSnap of its amplitude, nearest what `kind` (None
// with the spatial flag, and the smooth or Fit flag) predicts from the values chosen before it.
void snap_plane_fast(const FastTraversal& t, const FastFit& fit, const double* x, uint8_t kind, int32_t* plane) {
  std::vector<int64_t> e(t.order.size() * 3);
  const double limit = double(kMaxLowRankBasis);
  for (size_t pos = 0; pos < t.order.size(); ++pos) {
    int64_t p[3];
    if (fast_residual::is_fit(kind)) fast_fit_position(fit, pos, e.data(), p);
    else
      for (int a = 0; a < 3; ++a) p[a] = fast_spatial(t, pos, e.data(), a, fast_residual::is_smooth(kind));
    const size_t v = size_t(t.order[pos]) * 3;
    for (int a = 0; a < 3; ++a) {
      const size_t i = v + size_t(a);
      const double lo = std::max(std::ceil(x[i] - kBasisSnap), -limit), hi = std::min(std::floor(x[i] + kBasisSnap), limit);
      plane[i] = int32_t(std::clamp(double(p[a]), lo, std::max(lo, hi)));
      e[pos * 3 + size_t(a)] = plane[i];
    }
  }
}

// Least-squares coefficients of every frame of q against the quantized mean and basis
// (values: mean, then K basis vectors), in the model's units (prediction * 2^S). The PCA
// weights fit the unrounded basis; on a coarse basis step its rounding is a large part of
// the prediction error, and refitting removes what a linear combination can.
void refit_coefficients(const std::vector<int32_t>& q, const std::vector<int32_t>& values, uint32_t K, size_t n,
                        uint32_t S, uint32_t mean_shift, std::vector<double>* weights) {
  const size_t F = weights->size() / K;
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(K));
  for (uint32_t k = 0; k < K; ++k)
    for (size_t i = 0; i < n; ++i) B(Eigen::Index(i), Eigen::Index(k)) = values[(size_t(k) + 1) * n + i];
  const Eigen::LDLT<Eigen::MatrixXd> normal(B.transpose() * B);
  if (normal.info() != Eigen::Success) return;
  const double up = std::ldexp(1.0, int(S)), mean_up = std::ldexp(1.0, int(S - mean_shift));
  Eigen::VectorXd target = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  for (size_t f = 0; f < F; ++f) {
    for (size_t i = 0; i < n; ++i) target(Eigen::Index(i)) = double(q[f * n + i]) * up - double(values[i]) * mean_up;
    const Eigen::VectorXd c = normal.solve(B.transpose() * target);
    if (!c.allFinite()) continue;
    for (uint32_t k = 0; k < K; ++k) (*weights)[f * K + k] = c(Eigen::Index(k));
  }
}

// Per component, the coarsest coefficient unit 2^s (s <= S) whose rounding (at most 2^(s-1))
// moves no prediction by more than kCoefficientMove basis steps:
// max |basis_k| * 2^(s-1) / 2^S <= kCoefficientMove. Weak components (small basis values)
// get coarse coefficients. Half a step balances the two costs: finer coefficients (a
// quarter) cost more bytes than the residual saves on most inputs, coarser ones (a step)
// move predictions enough to cost residual bytes; and a unit per component codes smaller
// than one shared unit, which must suit the strongest component.
constexpr double kCoefficientMove = 0.5;
std::vector<uint8_t> coefficient_shifts(const std::vector<int32_t>& values, uint32_t K, size_t n, uint32_t S) {
  std::vector<uint8_t> shifts(K, 0);
  for (uint32_t k = 0; k < K; ++k) {
    int32_t largest = 0;
    for (size_t i = 0; i < n; ++i) largest = std::max(largest, std::abs(values[(size_t(k) + 1) * n + i]));
    uint32_t s = 0;
    while (s < S && double(largest) * std::ldexp(1.0, int(s)) <= kCoefficientMove * std::ldexp(1.0, int(S))) ++s;
    shifts[k] = uint8_t(s);
  }
  return shifts;
}

}  // namespace

std::vector<uint8_t> code_mean_and_basis_fast(const Model& model, std::vector<int32_t>* values_io,
                                              const std::vector<double>& exact) {
  const uint32_t frames = uint32_t(values_io->size() / (size_t(model.meta.vertex_count) * 3));
  using fast_residual::kFitFlag;
  using fast_residual::kSmoothFlag;
  using fast_residual::kSpatialFlag;
  std::vector<int32_t>& values = *values_io;
  const uint32_t V = model.meta.vertex_count;
  const size_t n = size_t(V) * 3;
  const FastTraversal t = fast_traversal(model.faces, V);
  const FastFit fit = fast_fit(model.faces, t, values.data());
  std::vector<uint8_t> kinds(frames, kSpatialFlag);
  size_t mean_best = SIZE_MAX;
  for (const uint8_t kind : {kSpatialFlag, uint8_t(kSpatialFlag | kSmoothFlag)}) {
    const size_t bytes = encode_fast_chunk(t, V, &kind, 1, values.data(), nullptr).size();
    if (bytes < mean_best) {
      mean_best = bytes;
      kinds[0] = kind;
    }
  }
  // A vector's bytes are measured as frame 1 of a chunk (Fit needs a frame before it; its
  // weights are the mean's, passed in) after a zero frame, which codes to almost nothing:
  // the mean is not coded again for every kind of every vector.
  std::vector<int32_t> pair(2 * n, 0);
  int32_t* trial = pair.data() + n;
  for (uint32_t k = 1; k < frames; ++k) {
    int32_t* plane = values.data() + k * n;
    size_t best = SIZE_MAX;
    for (const uint8_t kind : {kSpatialFlag, uint8_t(kSpatialFlag | kSmoothFlag), uint8_t(kSpatialFlag | kFitFlag)}) {
      std::copy(plane, plane + n, trial);
      if (!exact.empty()) snap_plane_fast(t, fit, exact.data() + (k - 1) * n, kind, trial);
      const uint8_t pair_kinds[2] = {kSpatialFlag, kind};
      const size_t bytes = encode_fast_chunk(t, V, pair_kinds, 2, pair.data(), nullptr, &fit).size();
      if (bytes < best) {
        best = bytes;
        kinds[k] = kind;
        std::copy(trial, trial + n, plane);
      }
    }
  }
  Model pseudo;
  pseudo.meta = model.meta;
  pseudo.meta.frame_count = frames;
  pseudo.faces = model.faces;
  return encode_fast_residuals(pseudo, values, kinds, frames, nullptr);
}

size_t anchor_bytes(const Model& model, std::vector<int32_t> values, int threads, const Traversal* traversal) {
  return code_mean_and_basis(model, &values, {}, 1, threads, nullptr, traversal).size();
}

bool quantize_low_rank(const GridComponents& pca, uint32_t K, double basis_step, uint32_t mean_shift, int threads,
                       Model* model, const std::vector<int32_t>* q, BasisMemo* memo,
                       const Traversal* traversal, CodedPayload* basis, BasisCoding coding) {
  const uint32_t F = model->meta.frame_count;
  const size_t n = pca.mean.size();
  if (K == 0 || K > pca.weights.size() || K > kMaxLowRankComponents || !(basis_step > 0)) return false;
  double max_amplitude = 0;
  for (uint32_t k = 0; k < K; ++k)
    for (double a : pca.amplitudes[k]) max_amplitude = std::max(max_amplitude, std::fabs(a));
  // A coefficient's rounding (<= 1/2) moves a prediction by max_amplitude / (2 step 2^S):
  // at most one basis step once 2^S >= max_amplitude / (2 step^2). Half a step costs more
  // coefficient bytes than it saves residual bytes; two steps move predictions enough to
  // cost more residual bytes than they save in coefficients.
  uint32_t S = mean_shift;
  while (S < kMaxLowRankShift && std::ldexp(1.0, int(S)) < max_amplitude / (2 * basis_step * basis_step)) ++S;
  const double scale = basis_step * std::ldexp(1.0, int(S));

  LowRankModel lr;
  lr.components = K;
  lr.shift = S;
  lr.mean_shift = mean_shift;
  std::vector<int32_t> values((size_t(K) + 1) * n);
  const double mean_scale = std::ldexp(1.0, int(mean_shift));
  for (size_t i = 0; i < n; ++i)
    if (!round_to(pca.mean[i] * mean_scale, INT32_MAX, &values[i])) return false;
  std::vector<double> exact(size_t(K) * n);
  for (uint32_t k = 0; k < K; ++k)
    for (size_t i = 0; i < n; ++i) {
      exact[size_t(k) * n + i] = pca.amplitudes[k][i] / basis_step;
      if (!round_to(exact[size_t(k) * n + i], kMaxLowRankBasis, &values[(size_t(k) + 1) * n + i])) return false;
    }
  BasisMemo::Entry* entry = nullptr;
  if (memo) {
    for (BasisMemo::Entry& e : memo->entries)
      if (e.basis_step == basis_step && e.mean_shift == mean_shift) entry = &e;
    if (!entry) {
      memo->entries.emplace_back();
      entry = &memo->entries.back();
      entry->basis_step = basis_step;
      entry->mean_shift = mean_shift;
    }
  }
  PredictorPlan plan;  // Range coding's
  lr.basis_payload = coding == BasisCoding::Fast
                         ? code_mean_and_basis_fast(*model, &values, exact)
                         : code_mean_and_basis(*model, &values, exact, K + 1, threads, entry, traversal, &plan);
  if (lr.basis_payload.empty()) return false;
  std::vector<double> weights(size_t(F) * K);
  for (uint32_t f = 0; f < F; ++f)
    for (uint32_t k = 0; k < K; ++k) weights[size_t(f) * K + k] = pca.weights[k][f] * scale;
  if (q) refit_coefficients(*q, values, K, n, S, mean_shift, &weights);
  lr.coeff_shifts = coefficient_shifts(values, K, n, S);
  lr.coeffs.resize(size_t(F) * K);
  for (size_t j = 0; j < weights.size(); ++j) {
    const double unit = std::ldexp(1.0, lr.coeff_shifts[j % K]);
    if (!round_to(std::nearbyint(weights[j] / unit) * unit, kMaxLowRankCoeff, &lr.coeffs[j])) return false;
  }
  lr.poses = pca.poses;
  std::copy(pca.pose_centre, pca.pose_centre + 3, lr.pose_centre);
  model->low_rank = std::move(lr);
  if (basis) {
    basis->plan = plan.frames.empty() ? ResidualPlan() : single_chunk_plan(plan);
    basis->values = std::move(values);
  }
  return true;
}

std::vector<int32_t> low_rank_prediction(const LowRankModel& lr, const std::vector<int32_t>& mean_and_basis, uint32_t F,
                                         size_t n) {
  std::vector<int32_t> out(size_t(F) * n);
  for (uint32_t f = 0; f < F; ++f) low_rank_frame(lr, f, mean_and_basis.data(), n, out.data() + size_t(f) * n);
  return out;
}

}  // namespace dcurve
