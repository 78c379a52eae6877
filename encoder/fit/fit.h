// Fitting one curve's motion with the closed-form PDE bases of codec/common/basis.h.
//
// Per axis, w(tau, u) = sum coeffs * T_i(tau) U_j(u): the coefficients are linear least squares
// (column-scaled SVD of the separable design, never normal equations); the basis case and the
// two nonlinear parameters are chosen by variable projection: a coarse grid over every case,
// then Levenberg-Marquardt on (time_param, space_param) for the best cases, minimizing the
// projected residual. Parameters are rounded to float before the final solve and the error is
// measured with the float coefficients evaluated through codec/common/basis: what a decoder would see.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/fit/rigid.h"

namespace dcurve {

// The samples of one curve: every point at every frame (a full grid).
struct CurveFrames {
  std::vector<double> u;     // per point, curve parameter in [0, 1]
  std::vector<double> tau;   // per frame, segment-local time in [0, 1], strictly increasing
  std::vector<double> xyz;   // positions, model units: xyz[(f * points + p) * 3 + axis]
  std::vector<double> rest;  // Displacement mode only: points * 3 rest positions (the decoder's
                             // reconstructed frame 0); the fit models xyz - rest
  size_t points() const { return u.size(); }
  size_t frames() const { return tau.size(); }
};

struct FitOptions {
  Basis basis = Basis::Pde8;         // Pde8 or Pde32
  FitMode mode = FitMode::Absolute;
  bool remove_rigid = false;         // 2024 paper: fit in a per-frame rigidly aligned frame (rigid.h)
  int fixed_case = -1;               // >= 0: use this case only (Pde8: 0..3)
  double fixed_time_param = -1;      // >= 0: no search over mu / alpha
  double fixed_space_param = -1;     // >= 0: no search over delta / r
  double max_time_param = 30;        // search range [0, max], <= kBasisMaxParam
  double max_space_param = 40;
  int coarse_time_steps = 10;        // grid: 0 and geometric steps up to max
  int coarse_space_steps = 14;
  int refined_cases = 2;             // best coarse cases refined by Levenberg-Marquardt
  int refine_iterations = 30;
  // Time parameter by held-out frames: each candidate's time_param is the value of the
  // coarse grid (or the refined one) that best predicts each fitted frame from the others
  // (case and space parameter as searched; param_search.h, leave_out_error2). A fit that matches the samples closely
  // may alias between them; this choice targets the frames between. Needs 3+ frames.
  bool time_param_by_leave_out = false;
};

struct AxisFit {
  CurveMotion motion;           // as stored: float parameters and coefficients
  std::vector<double> coeffs;   // the double least-squares solution at the float parameters
  double residual_rms = 0;      // of the double solution over the samples, model units
};

struct CurveFit {
  AxisFit axis[3];
  RigidTrack rigid;       // empty keys unless FitOptions::remove_rigid
  FitMode mode = FitMode::Absolute;
  // Point distances between the input and the stored fit (float motion through codec/common/basis,
  // rest pose and rigid motion restored) at the fitted frames, model units.
  double rms_error = 0;
  double max_error = 0;
};

// Fits the three axes of one curve. Fails (with a message) on inconsistent sizes, fewer than
// one point or frame, tau outside [0, 1] or not increasing, non-finite input, or a missing rest
// pose in Displacement mode.
bool fit_curve(const CurveFrames& curve, const FitOptions& options, CurveFit* fit, std::string* error);

// Positions of the fitted curve at segment time tau for the points u (world coordinates:
// rest pose and rigid motion restored), written to xyz (u.size() * 3), model units.
// `rest` (points * 3) is added in Displacement mode; a rest of any other size is ignored
// (the displacement alone is returned), never read out of bounds.
void evaluate_curve_fit(const CurveFit& fit, const std::vector<double>& u, const std::vector<double>& rest,
                        double tau, double* xyz);

// Fits many curves on `threads` threads (0: hardware concurrency). fits[i] depends only on
// curves[i] and the options, never on the thread count. On failure, error names the curve.
bool fit_curves(const std::vector<CurveFrames>& curves, const FitOptions& options, int threads,
                std::vector<CurveFit>* fits, std::string* error);

}  // namespace dcurve
