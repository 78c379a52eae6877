#include "encoder/fit/fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "codec/common/basis.h"
#include "codec/common/error.h"
#include "encoder/fit/param_search.h"
#include "encoder/fit/projection.h"
#include "encoder/parallel.h"

namespace dcurve {
namespace {

bool check_input(const CurveFrames& c, const FitOptions& o, std::string* error) {
  const size_t P = c.points(), F = c.frames();
  if (o.basis != Basis::Pde8 && o.basis != Basis::Pde32) return fail(error, "fit: basis must be Pde8 or Pde32");
  if (o.basis == Basis::Pde8 && o.fixed_case > 3) return fail(error, "fit: Pde8 basis case must be 0..3");
  if (o.basis == Basis::Pde32 && o.fixed_case > 0) return fail(error, "fit: Pde32 has only basis case 0");
  if (o.max_time_param < 0 || o.max_time_param > kBasisMaxParam || o.max_space_param < 0 ||
      o.max_space_param > kBasisMaxParam || o.fixed_time_param > kBasisMaxParam ||
      o.fixed_space_param > kBasisMaxParam)
    return fail(error, "fit: parameters must lie in [0, 1000]");
  if (P == 0 || F == 0) return fail(error, "fit: a curve needs at least one point and one frame");
  if (c.xyz.size() != P * F * 3) return fail(error, "fit: xyz must hold points * frames * 3 values");
  if (o.mode == FitMode::Displacement && c.rest.size() != P * 3)
    return fail(error, "fit: displacement mode needs points * 3 rest positions");
  for (size_t f = 0; f < F; ++f) {
    if (!(c.tau[f] >= 0 && c.tau[f] <= 1)) return fail(error, "fit: tau must lie in [0, 1]");
    if (f > 0 && !(c.tau[f] > c.tau[f - 1])) return fail(error, "fit: tau must be strictly increasing");
  }
  for (double u : c.u)
    if (!(u >= 0 && u <= 1)) return fail(error, "fit: u must lie in [0, 1]");
  for (double v : c.xyz)
    if (!std::isfinite(v)) return fail(error, "fit: non-finite position");
  for (double v : c.rest)
    if (!std::isfinite(v)) return fail(error, "fit: non-finite rest position");
  return true;
}

// The stored motions evaluated through codec/common/basis on the sample grid, rest and rigid restored.
void evaluate_on_grid(const CurveFit& fit, const CurveFrames& c, std::vector<double>* out) {
  const size_t P = c.points(), F = c.frames();
  out->resize(P * F * 3);
  for (size_t f = 0; f < F; ++f) evaluate_curve_fit(fit, c.u, c.rest, c.tau[f], out->data() + f * P * 3);
}

// Least squares at the choice's parameters rounded to float, as the file will hold them;
// stored2 = squared residual of the float coefficients.
AxisFit solve_axis(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau, Basis basis,
                   const ParamChoice& choice, double* stored2) {
  AxisFit ax;
  CurveMotion& m = ax.motion;
  m.basis = basis;
  m.basis_case = uint8_t(choice.basis_case);
  m.time_param = float(choice.time_param);
  m.space_param = float(choice.space_param);
  Eigen::MatrixXd space_m = space_design(basis, m.basis_case, m.space_param, u);
  Eigen::MatrixXd time_m = time_design(basis, m.basis_case, m.time_param, tau);
  ScaledRange space, time;
  space.compute(space_m, true);
  time.compute(time_m, true);
  Eigen::VectorXd coeffs = solve_coefficients(space, time, w);
  ax.coeffs.assign(coeffs.data(), coeffs.data() + coeffs.size());
  m.coeffs.resize(ax.coeffs.size());
  for (size_t k = 0; k < ax.coeffs.size(); ++k) m.coeffs[k] = float(ax.coeffs[k]);
  ax.residual_rms = std::sqrt(projection_residual(space, time, w).squaredNorm() / double(w.size()));
  const Eigen::Index ns = space_m.cols(), nt = time_m.cols();
  Eigen::MatrixXd stored(ns, nt);  // space x time, from the float coefficients
  for (Eigen::Index i = 0; i < nt; ++i)
    for (Eigen::Index j = 0; j < ns; ++j) stored(j, i) = double(m.coeffs[size_t(i * ns + j)]);
  *stored2 = (w - space_m * stored * time_m.transpose()).squaredNorm();
  return ax;
}

}  // namespace

void evaluate_curve_fit(const CurveFit& fit, const std::vector<double>& u, const std::vector<double>& rest,
                        double tau, double* xyz) {
  const size_t P = u.size();
  const bool add_rest = fit.mode == FitMode::Displacement && rest.size() == P * 3;
  for (int a = 0; a < 3; ++a) {
    const CurveMotion& m = fit.axis[a].motion;
    const int nt = basis_time_count(m.basis), ns = basis_space_count(m.basis);
    double t[4] = {0, 0, 0, 0}, s[8];
    if (nt > 0) basis_time(m.basis, m.basis_case, m.time_param, tau, t);
    double row[8] = {0, 0, 0, 0, 0, 0, 0, 0};  // sum_i coeff(i, j) T_i(tau)
    if (m.coeffs.size() == size_t(nt * ns))
      for (int i = 0; i < nt; ++i)
        for (int j = 0; j < ns; ++j) row[j] += double(m.coeffs[size_t(i * ns + j)]) * t[i];
    for (size_t p = 0; p < P; ++p) {
      double w = 0;
      if (ns > 0) {
        basis_space(m.basis, m.basis_case, m.space_param, u[p], s);
        for (int j = 0; j < ns; ++j) w += row[j] * s[j];
      }
      if (add_rest) w += rest[p * 3 + size_t(a)];
      xyz[p * 3 + size_t(a)] = w;
    }
  }
  apply_rigid(fit.rigid, tau, P, xyz);
}

bool fit_curve(const CurveFrames& c, const FitOptions& o, CurveFit* fit, std::string* error) {
  if (!check_input(c, o, error)) return false;
  const size_t P = c.points(), F = c.frames();
  *fit = CurveFit();
  fit->mode = o.mode;

  std::vector<double> local;
  const std::vector<double>* positions = &c.xyz;
  if (o.remove_rigid) {
    remove_rigid_motion(c.xyz, c.tau, P, &fit->rigid, &local);
    positions = &local;
  }
  Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(c.u.data(), Eigen::Index(P));
  Eigen::VectorXd tau = Eigen::Map<const Eigen::VectorXd>(c.tau.data(), Eigen::Index(F));
  std::array<Eigen::MatrixXd, 3> w;
  for (int a = 0; a < 3; ++a) {
    w[size_t(a)].resize(Eigen::Index(P), Eigen::Index(F));
    for (size_t f = 0; f < F; ++f)
      for (size_t p = 0; p < P; ++p) {
        double v = (*positions)[(f * P + p) * 3 + size_t(a)];
        if (o.mode == FitMode::Displacement) v -= c.rest[p * 3 + size_t(a)];
        w[size_t(a)](Eigen::Index(p), Eigen::Index(f)) = v;
      }
  }

  // The search ranks candidates by the double residual; the file holds floats, and an
  // ill-conditioned candidate (say, as many points as space functions at a large parameter)
  // can fit in double and fall apart in float. So each candidate, and the polynomial limit
  // (parameters 0, or the fixed ones) as a safe fallback, is judged by its stored residual.
  std::array<std::vector<ParamChoice>, 3> candidates = search_parameters(w, u, tau, o);
  for (int a = 0; a < 3; ++a) {
    std::vector<ParamChoice>& list = candidates[size_t(a)];
    ParamChoice fallback = list.front();
    fallback.time_param = std::max(0.0, o.fixed_time_param);
    fallback.space_param = std::max(0.0, o.fixed_space_param);
    list.push_back(fallback);
    double best = std::numeric_limits<double>::infinity();
    for (const ParamChoice& pc : list) {
      double stored2 = 0;
      AxisFit candidate = solve_axis(w[size_t(a)], u, tau, o.basis, pc, &stored2);
      if (stored2 < best) {
        best = stored2;
        fit->axis[a] = candidate;
      }
    }
  }

  std::vector<double> fitted;
  evaluate_on_grid(*fit, c, &fitted);
  double sum2 = 0, worst = 0;
  for (size_t k = 0; k < P * F; ++k) {
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      double d = fitted[k * 3 + size_t(a)] - c.xyz[k * 3 + size_t(a)];
      d2 += d * d;
    }
    sum2 += d2;
    worst = std::max(worst, d2);
  }
  fit->rms_error = std::sqrt(sum2 / double(P * F));
  fit->max_error = std::sqrt(worst);
  return true;
}

bool fit_curves(const std::vector<CurveFrames>& curves, const FitOptions& options, int threads,
                std::vector<CurveFit>* fits, std::string* error) {
  fits->assign(curves.size(), CurveFit());
  std::vector<std::string> errors(curves.size());
  std::vector<char> ok(curves.size(), 0);
  parallel_for(curves.size(), threads,
               [&](size_t i) { ok[i] = fit_curve(curves[i], options, &(*fits)[i], &errors[i]) ? 1 : 0; });
  for (size_t i = 0; i < curves.size(); ++i)
    if (!ok[i]) return fail(error, "curve " + std::to_string(i) + ": " + errors[i]);
  return true;
}

}  // namespace dcurve
