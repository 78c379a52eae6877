#include "encoder/fit/projection.h"

#include <algorithm>
#include <cmath>

#include "codec/common/basis.h"

namespace dcurve {

void ScaledRange::compute(const Eigen::MatrixXd& a, bool want_pinv) {
  Eigen::VectorXd scale(a.cols());
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    double n = a.col(j).norm();
    scale(j) = n > 0 ? 1.0 / n : 1.0;
  }
  Eigen::MatrixXd scaled = a * scale.asDiagonal();
  if (!want_pinv) {
    // The search needs only the range: a pivoted QR gives it at a fraction of the SVD's cost;
    // the diagonal of R, relative to its first entry, decides the rank as the singular values do.
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(scaled);
    const Eigen::Index k = std::min(scaled.rows(), scaled.cols());
    Eigen::Index rank = 0;
    const double r0 = k > 0 ? std::abs(qr.matrixR()(0, 0)) : 0.0;
    while (rank < k && std::abs(qr.matrixR()(rank, rank)) > r0 * 1e-11) ++rank;
    q = qr.householderQ() * Eigen::MatrixXd::Identity(scaled.rows(), rank);
    return;
  }
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

namespace {
// basis_space and basis_time share one signature: sample either on the points x.
using BasisFn = void (*)(Basis, int, double, double, double*);
Eigen::MatrixXd sample_design(BasisFn fn, int count, Basis b, int basis_case, double param, const Eigen::VectorXd& x) {
  Eigen::MatrixXd m(x.size(), count);
  double out[8];
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    fn(b, basis_case, param, x(k), out);
    for (Eigen::Index j = 0; j < count; ++j) m(k, j) = out[j];
  }
  return m;
}
}  // namespace

Eigen::MatrixXd space_design(Basis b, int basis_case, double space_param, const Eigen::VectorXd& u) {
  return sample_design(basis_space, basis_space_count(b), b, basis_case, space_param, u);
}

Eigen::MatrixXd time_design(Basis b, int basis_case, double time_param, const Eigen::VectorXd& tau) {
  return sample_design(basis_time, basis_time_count(b), b, basis_case, time_param, tau);
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
