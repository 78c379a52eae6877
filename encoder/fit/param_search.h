// The nonlinear half of variable projection: choose the basis case and (time_param,
// space_param) of each axis by minimizing the projected residual |W - P_U W P_T|.
#pragma once
#include <Eigen/Dense>
#include <array>
#include <vector>

#include "encoder/fit/fit.h"

namespace dcurve {

struct ParamChoice {
  int basis_case = 0;
  double time_param = 0;
  double space_param = 0;
  double residual2 = 0;  // squared residual norm at the choice, model units^2
};

// Candidate choices per axis for the three points x frames matrices w[a], best first. Coarse
// grid over every allowed case (the three axes share the basis evaluations), then
// Levenberg-Marquardt on the free parameters of the options.refined_cases best cases of each
// axis (one refined candidate per case); with options.time_param_by_leave_out the time
// parameter of each candidate is then re-chosen by leave_out_error2. Deterministic.
std::array<std::vector<ParamChoice>, 3> search_parameters(const std::array<Eigen::MatrixXd, 3>& w, const Eigen::VectorXd& u,
                                             const Eigen::VectorXd& tau, const FitOptions& options);

// Leave-one-out error of one axis at one choice: the squared distance, summed over the
// frames k, between frame k and the fit of the other frames evaluated at tau[k]. The end
// frames count too: a time function that only an end frame sees (e^{-alpha tau} at large
// alpha is nearly an indicator of frame 0) predicts nothing once that frame is left out.
// Infinity with fewer than 3 frames.
double leave_out_error2(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau, Basis basis,
                        int basis_case, double time_param, double space_param);

// Squared projected residual of one axis at one choice (the quantity searched).
double projected_residual2(const Eigen::MatrixXd& w, const Eigen::VectorXd& u, const Eigen::VectorXd& tau,
                           Basis basis, int basis_case, double time_param, double space_param);

}  // namespace dcurve
