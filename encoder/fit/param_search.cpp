#include "encoder/fit/param_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "codec/common/basis.h"
#include "encoder/fit/projection.h"

namespace dcurve {
namespace {

// Which sign bits a case uses: Pde8 time is trigonometric for bit 1, space damped for bit 0.
int time_variant(Basis b, int c) { return b == Basis::Pde8 ? (c >> 1) & 1 : 0; }
int space_variant(Basis b, int c) { return b == Basis::Pde8 ? c & 1 : 0; }
// A representative case with the given time / space variant, for evaluating the design.
int case_for_time(int variant) { return variant << 1; }
int case_for_space(int variant) { return variant; }

// 0 and steps - 1 geometric values from 0.25 to max; a fixed value alone when fixed >= 0.
std::vector<double> grid(double fixed, double max, int steps) {
  if (fixed >= 0) return {fixed};
  std::vector<double> g = {0.0};
  if (max <= 0 || steps < 2) return g;
  const double lo = std::min(0.25, max);
  if (steps == 2) return {0.0, max};
  double ratio = std::pow(max / lo, 1.0 / (steps - 2));
  for (int k = 0; k < steps - 1; ++k) g.push_back(k == steps - 2 ? max : lo * std::pow(ratio, k));
  return g;
}

std::vector<int> allowed_cases(const FitOptions& o) {
  if (o.basis != Basis::Pde8) return {0};
  if (o.fixed_case >= 0) return {o.fixed_case};
  return {0, 1, 2, 3};
}

// Residual evaluation with a one-entry cache per factor: finite differences move one
// parameter at a time, so the other factor's SVD is reused.
class ResidualModel {
 public:
  ResidualModel(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau, Basis b, int c)
      : w_(w), u_(u), tau_(tau), basis_(b), case_(c) {}

  Eigen::VectorXd residual(double time_param, double space_param) {
    if (!has_space_ || space_param != space_param_) {
      space_.compute(space_design(basis_, case_, space_param, u_), false);
      space_param_ = space_param;
      has_space_ = true;
    }
    if (!has_time_ || time_param != time_param_) {
      time_.compute(time_design(basis_, case_, time_param, tau_), false);
      time_param_ = time_param;
      has_time_ = true;
    }
    return projection_residual(space_, time_, w_);
  }

 private:
  const Eigen::MatrixXd& w_;
  const Eigen::VectorXd& u_;
  const Eigen::VectorXd& tau_;
  Basis basis_;
  int case_;
  ScaledRange space_, time_;
  double space_param_ = 0, time_param_ = 0;
  bool has_space_ = false, has_time_ = false;
};

// Levenberg-Marquardt on the free parameters (x[0] = time, x[1] = space), bounded to
// [0, max] by clamping, central-difference Jacobian. Returns the best point seen.
ParamChoice refine(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                   const FitOptions& o, ParamChoice start) {
  ResidualModel model(w, u, tau, o.basis, start.basis_case);
  const bool free_param[2] = {o.fixed_time_param < 0, o.fixed_space_param < 0};
  const double upper[2] = {o.max_time_param, o.max_space_param};
  double x[2] = {start.time_param, start.space_param};
  Eigen::VectorXd r = model.residual(x[0], x[1]);
  double cost = r.squaredNorm();
  const double floor = 1e-30 * std::max(w.squaredNorm(), std::numeric_limits<double>::min());
  double lambda = 1e-3;
  for (int it = 0; it < o.refine_iterations && cost > floor; ++it) {
    Eigen::MatrixXd jac = Eigen::MatrixXd::Zero(r.size(), 2);
    for (int k = 0; k < 2; ++k) {
      if (!free_param[k]) continue;
      double h = 1e-5 * std::max(1.0, x[k]);
      double xp[2] = {x[0], x[1]}, xm[2] = {x[0], x[1]};
      xp[k] += h;
      xm[k] -= h;
      jac.col(k) = (model.residual(xp[0], xp[1]) - model.residual(xm[0], xm[1])) / (2 * h);
    }
    Eigen::Matrix2d jtj = jac.transpose() * jac;
    Eigen::Vector2d g = jac.transpose() * r;
    if (g.norm() == 0) break;
    bool improved = false;
    for (int tries = 0; tries < 8 && !improved; ++tries) {
      Eigen::Matrix2d a = jtj;
      for (int k = 0; k < 2; ++k) a(k, k) += lambda * std::max(jtj(k, k), 1e-300) + (free_param[k] ? 0.0 : 1.0);
      Eigen::Vector2d step = -a.ldlt().solve(g);
      double xn[2];
      for (int k = 0; k < 2; ++k) xn[k] = free_param[k] ? std::clamp(x[k] + step(k), 0.0, upper[k]) : x[k];
      Eigen::VectorXd rn = model.residual(xn[0], xn[1]);
      double cn = rn.squaredNorm();
      if (cn < cost) {
        // Stop once the parameters or the residual no longer move: a further gain below one
        // part in 1e10 of the residual changes no stored float.
        bool tiny = (std::fabs(xn[0] - x[0]) <= 1e-13 * (1 + x[0]) && std::fabs(xn[1] - x[1]) <= 1e-13 * (1 + x[1])) ||
                    cost - cn <= 1e-10 * cost;
        x[0] = xn[0];
        x[1] = xn[1];
        r = rn;
        cost = cn;
        lambda = std::max(lambda / 4, 1e-12);
        improved = true;
        if (tiny) it = o.refine_iterations;
      } else {
        lambda *= 8;
      }
    }
    if (!improved) break;
  }
  start.time_param = x[0];
  start.space_param = x[1];
  start.residual2 = cost;
  return start;
}

// Re-chooses c.time_param among `tgrid` and its own value by leave_out_error2, its space
// parameter and case fixed; residual2 follows the new value.
ParamChoice time_param_left_out(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                                Basis b, const std::vector<double>& tgrid, ParamChoice c) {
  double best = leave_out_error2(w, u, tau, b, c.basis_case, c.time_param, c.space_param);
  const double refined = c.time_param;
  for (double mu : tgrid) {
    const double e = leave_out_error2(w, u, tau, b, c.basis_case, mu, c.space_param);
    if (e < best) {
      best = e;
      c.time_param = mu;
    }
  }
  if (c.time_param != refined) c.residual2 = projected_residual2(w, u, tau, b, c.basis_case, c.time_param, c.space_param);
  return c;
}

}  // namespace

double leave_out_error2(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau, Basis basis,
                        int basis_case, double time_param, double space_param) {
  const Eigen::Index F = tau.size();
  if (F < 3) return std::numeric_limits<double>::infinity();
  ScaledRange space;
  space.compute(space_design(basis, basis_case, space_param, u), false);
  const Eigen::MatrixXd z = space.q.transpose() * w;  // space-projected samples, rank x frames
  // What the space functions cannot reach is missed at every frame, whatever the time fit.
  double sum = (w - space.q * z).squaredNorm();
  const Eigen::MatrixXd t = time_design(basis, basis_case, time_param, tau);
  for (Eigen::Index k = 0; k < F; ++k) {
    Eigen::MatrixXd t_others(F - 1, t.cols()), z_others(z.rows(), F - 1);
    t_others << t.topRows(k), t.bottomRows(F - 1 - k);
    z_others << z.leftCols(k), z.rightCols(F - 1 - k);
    ScaledRange time;
    time.compute(t_others, true);
    sum += (z.col(k) - z_others * time.pinv.transpose() * t.row(k).transpose()).squaredNorm();
  }
  return sum;
}

double projected_residual2(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                           Basis basis, int basis_case, double time_param, double space_param) {
  ResidualModel model(w, u, tau, basis, basis_case);
  return model.residual(time_param, space_param).squaredNorm();
}

std::array<std::vector<ParamChoice>, 3> search_parameters(const std::array<Eigen::MatrixXd, 3>& w, const Eigen::VectorXd& u,
                                             const Eigen::VectorXd& tau, const FitOptions& o) {
  const Basis b = o.basis;
  const std::vector<int> cases = allowed_cases(o);
  const std::vector<double> tgrid = grid(o.fixed_time_param, o.max_time_param, o.coarse_time_steps);
  const std::vector<double> sgrid = grid(o.fixed_space_param, o.max_space_param, o.coarse_space_steps);
  double total2[3];
  for (int a = 0; a < 3; ++a) total2[a] = w[a].squaredNorm();

  // Time factors for both variants, computed once.
  std::vector<ScaledRange> time_ranges[2];
  for (int tv = 0; tv < 2; ++tv) {
    bool used = std::any_of(cases.begin(), cases.end(), [&](int c) { return time_variant(b, c) == tv; });
    if (!used) continue;
    for (double mu : tgrid) {
      time_ranges[tv].emplace_back();
      time_ranges[tv].back().compute(time_design(b, case_for_time(tv), mu, tau), false);
    }
  }
  // best[a][case] from the coarse grid
  std::vector<std::array<ParamChoice, 3>> best(4);
  for (auto& per_axis : best)
    for (auto& pc : per_axis) pc.residual2 = std::numeric_limits<double>::infinity();
  for (int sv = 0; sv < 2; ++sv) {
    bool used = std::any_of(cases.begin(), cases.end(), [&](int c) { return space_variant(b, c) == sv; });
    if (!used) continue;
    for (double delta : sgrid) {
      ScaledRange space;
      space.compute(space_design(b, case_for_space(sv), delta, u), false);
      Eigen::MatrixXd wq[3];
      for (int a = 0; a < 3; ++a) wq[a] = space.q.transpose() * w[a];
      for (int c : cases) {
        if (space_variant(b, c) != sv) continue;
        int tv = time_variant(b, c);
        for (size_t k = 0; k < tgrid.size(); ++k) {
          for (int a = 0; a < 3; ++a) {
            double r2 = total2[a] - (wq[a] * time_ranges[tv][k].q).squaredNorm();
            ParamChoice& pc = best[size_t(c)][size_t(a)];
            if (r2 < pc.residual2) pc = ParamChoice{c, tgrid[k], delta, r2};
          }
        }
      }
    }
  }

  std::array<std::vector<ParamChoice>, 3> chosen;
  for (int a = 0; a < 3; ++a) {
    std::vector<ParamChoice> ranked;
    for (int c : cases) ranked.push_back(best[size_t(c)][size_t(a)]);
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const ParamChoice& x, const ParamChoice& y) { return x.residual2 < y.residual2; });
    std::vector<ParamChoice>& out = chosen[size_t(a)];
    size_t n = std::min(ranked.size(), size_t(std::max(1, o.refined_cases)));
    for (size_t k = 0; k < n; ++k) {
      out.push_back(refine(w[size_t(a)], u, tau, o, ranked[k]));
      if (o.time_param_by_leave_out && o.fixed_time_param < 0 && tau.size() >= 3)
        out.back() = time_param_left_out(w[size_t(a)], u, tau, b, tgrid, out.back());
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const ParamChoice& x, const ParamChoice& y) { return x.residual2 < y.residual2; });
  }
  return chosen;
}

}  // namespace dcurve
