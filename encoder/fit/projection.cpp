#include "encoder/fit/projection.h"

#include "codec/basis.h"

namespace dcurve {

void ScaledRange::compute(const Eigen::MatrixXd& a, bool want_pinv) {
  Eigen::VectorXd scale(a.cols());
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    double n = a.col(j).norm();
    scale(j) = n > 0 ? 1.0 / n : 1.0;
  }
  Eigen::MatrixXd scaled = a * scale.asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index rank = 0;
  double cut = s.size() > 0 ? s(0) * 1e-11 : 0.0;
  while (rank < s.size() && s(rank) > cut) ++rank;
  q = svd.matrixU().leftCols(rank);
  if (want_pinv) {
    pinv = scale.asDiagonal() * svd.matrixV().leftCols(rank) *
           s.head(rank).cwiseInverse().asDiagonal() * q.transpose();
  }
}

Eigen::MatrixXd space_design(Basis b, int basis_case, double space_param, const Eigen::VectorXd& u) {
  Eigen::MatrixXd m(u.size(), basis_space_count(b));
  double out[8];
  for (Eigen::Index p = 0; p < u.size(); ++p) {
    basis_space(b, basis_case, space_param, u(p), out);
    for (Eigen::Index j = 0; j < m.cols(); ++j) m(p, j) = out[j];
  }
  return m;
}

Eigen::MatrixXd time_design(Basis b, int basis_case, double time_param, const Eigen::VectorXd& tau) {
  Eigen::MatrixXd m(tau.size(), basis_time_count(b));
  double out[4];
  for (Eigen::Index f = 0; f < tau.size(); ++f) {
    basis_time(b, basis_case, time_param, tau(f), out);
    for (Eigen::Index i = 0; i < m.cols(); ++i) m(f, i) = out[i];
  }
  return m;
}

Eigen::VectorXd projection_residual(const ScaledRange& space, const ScaledRange& time, const Eigen::MatrixXd& w) {
  Eigen::MatrixXd fitted = space.q * ((space.q.transpose() * w) * time.q) * time.q.transpose();
  Eigen::MatrixXd r = w - fitted;
  return Eigen::Map<Eigen::VectorXd>(r.data(), r.size());
}

Eigen::VectorXd solve_coefficients(const ScaledRange& space, const ScaledRange& time, const Eigen::MatrixXd& w) {
  Eigen::MatrixXd c = space.pinv * w * time.pinv.transpose();  // space_count x time_count
  Eigen::VectorXd out(c.size());
  for (Eigen::Index i = 0; i < c.cols(); ++i)
    for (Eigen::Index j = 0; j < c.rows(); ++j) out(i * c.rows() + j) = c(j, i);
  return out;
}

}  // namespace dcurve
