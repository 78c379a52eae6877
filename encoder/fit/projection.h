// The linear half of variable projection. For fixed case and parameters the design of one
// axis is separable, W = U C T^T (U: points x space functions, T: frames x time functions,
// C: coefficients), so the least-squares solution is C = U^+ W T^+T and the fitted values are
// P_U W P_T with P the orthogonal projectors. Pseudo-inverses come from a column-scaled SVD:
// no normal equations, and columns of very different size (large parameters) are harmless.
#pragma once
#include <Eigen/Dense>

#include "codec/common/model.h"

namespace dcurve {

// Range basis and pseudo-inverse of a matrix (rows >= 1, columns <= 8), after scaling every
// column to unit norm. With the pseudo-inverse: SVD, singular values below 1e-11 of the
// largest count as zero, so rank-deficient designs (fewer frames than time functions) get the
// minimum-norm solution. Range only (the parameter search): pivoted QR, same 1e-11 rank rule
// on the diagonal of R.
struct ScaledRange {
  Eigen::MatrixXd q;      // rows x rank, orthonormal columns spanning the matrix's range
  Eigen::MatrixXd pinv;   // columns x rows: pseudo-inverse of the unscaled matrix
  void compute(const Eigen::MatrixXd& a, bool want_pinv);
};

// Samples of the space functions (points x count) and time functions (frames x count).
Eigen::MatrixXd space_design(Basis b, int basis_case, double space_param, const Eigen::VectorXd& u);
Eigen::MatrixXd time_design(Basis b, int basis_case, double time_param, const Eigen::VectorXd& tau);

// Residual W - P_U W P_T as a points*frames vector (column-major), model units.
Eigen::VectorXd projection_residual(const ScaledRange& space, const ScaledRange& time, const Eigen::MatrixXd& w);

// Least-squares coefficients, laid out as codec/common/basis.h says: coeffs[i_time * space_count + i_space].
Eigen::VectorXd solve_coefficients(const ScaledRange& space, const ScaledRange& time, const Eigen::MatrixXd& w);

}  // namespace dcurve
