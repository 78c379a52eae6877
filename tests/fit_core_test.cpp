// encoder/fit: known motions are recovered, the PDE fit never loses to the polynomial limit it
// contains, rigid motion is removed and restored, results do not depend on the thread count.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>

#include "codec/common/basis.h"
#include "encoder/fit/fit.h"
#include "encoder/fit/param_search.h"

namespace dcurve {
namespace {

// A curve of `points` samples at `frames` equally spaced tau, positions from w(a, tau, u).
template <class Fn>
CurveFrames make_curve(size_t points, size_t frames, Fn w) {
  CurveFrames c;
  for (size_t p = 0; p < points; ++p) c.u.push_back(double(p) / double(points - 1));
  for (size_t f = 0; f < frames; ++f) c.tau.push_back(frames == 1 ? 0.0 : double(f) / double(frames - 1));
  for (size_t f = 0; f < frames; ++f)
    for (size_t p = 0; p < points; ++p)
      for (int a = 0; a < 3; ++a) c.xyz.push_back(w(a, c.tau[f], c.u[p]));
  return c;
}

double motion_value(Basis b, int c, double tp, double sp, const std::vector<double>& coeffs, double tau, double u) {
  double t[4], s[8];
  basis_time(b, c, tp, tau, t);
  basis_space(b, c, sp, u, s);
  int nt = basis_time_count(b), ns = basis_space_count(b);
  double w = 0;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < ns; ++j) w += coeffs[size_t(i * ns + j)] * t[i] * s[j];
  return w;
}

std::vector<double> random_coeffs(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> d(-1, 1);
  std::vector<double> c(static_cast<size_t>(n));
  for (double& v : c) v = d(rng);
  return c;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (size_t k = 0; k < a.size(); ++k) m = std::max(m, std::fabs(a[k] - b[k]));
  return m;
}

// max_k |a_k - b_k| * (largest |T_i| over the frames) * (largest |U_j| over the points): each
// coefficient's error weighted by the size of its term. For Pde32 at small parameters the
// top terms are ~v^7/7! and ~s^3/6, so their raw coefficients are determined only to that scale.
double weighted_coeff_error(const CurveFrames& c, const CurveMotion& m, const std::vector<double>& a,
                            const std::vector<double>& b) {
  int nt = basis_time_count(m.basis), ns = basis_space_count(m.basis);
  std::vector<double> tmax(size_t(nt), 0.0), smax(size_t(ns), 0.0);
  double t[4], s[8];
  for (double tau : c.tau) {
    basis_time(m.basis, m.basis_case, m.time_param, tau, t);
    for (int i = 0; i < nt; ++i) tmax[size_t(i)] = std::max(tmax[size_t(i)], std::fabs(t[i]));
  }
  for (double u : c.u) {
    basis_space(m.basis, m.basis_case, m.space_param, u, s);
    for (int j = 0; j < ns; ++j) smax[size_t(j)] = std::max(smax[size_t(j)], std::fabs(s[j]));
  }
  double worst = 0;
  for (int i = 0; i < nt; ++i)
    for (int j = 0; j < ns; ++j) {
      size_t k = size_t(i * ns + j);
      worst = std::max(worst, std::fabs(a[k] - b[k]) * tmax[size_t(i)] * smax[size_t(j)]);
    }
  return worst;
}

// Coefficient error as the issue states it (< 1e-8) for Pde8; term-weighted for Pde32.
double coeff_error(const CurveFrames& c, const AxisFit& fit, const std::vector<double>& truth) {
  if (fit.motion.basis == Basis::Pde8) return max_abs_diff(fit.coeffs, truth);
  return weighted_coeff_error(c, fit.motion, fit.coeffs, truth);
}

struct Truth {
  Basis basis;
  int basis_case;
  double time_param, space_param;  // float-representable, so the stored parameters are exact
};

// Random coefficients per axis (into coeffs) and the curve they generate under `t`.
CurveFrames curve_from_truth(const Truth& t, std::mt19937& rng, size_t points, size_t frames,
                             std::vector<double> coeffs[3]) {
  for (int a = 0; a < 3; ++a) coeffs[a] = random_coeffs(rng, basis_term_count(t.basis));
  return make_curve(points, frames, [&](int a, double tau, double u) {
    return motion_value(t.basis, t.basis_case, t.time_param, t.space_param, coeffs[a], tau, u);
  });
}

TEST(FitCore, RecoversKnownCoefficientsAtKnownParameters) {
  std::mt19937 rng(7);
  const Truth cases[] = {{Basis::Pde8, 0, 3.25, 5.5}, {Basis::Pde8, 1, 0.0, 2.75}, {Basis::Pde8, 2, 6.5, 0.0},
                         {Basis::Pde8, 3, 12.5, 20.0}, {Basis::Pde32, 0, 2.5, 6.0}, {Basis::Pde32, 0, 9.5, 11.0}};
  for (const Truth& t : cases) {
    std::vector<double> coeffs[3];
    CurveFrames curve = curve_from_truth(t, rng, 30, 7, coeffs);
    FitOptions o;
    o.basis = t.basis;
    o.fixed_case = t.basis_case;
    o.fixed_time_param = t.time_param;
    o.fixed_space_param = t.space_param;
    CurveFit fit;
    std::string error;
    ASSERT_TRUE(fit_curve(curve, o, &fit, &error)) << error;
    for (int a = 0; a < 3; ++a) {
      EXPECT_LT(coeff_error(curve, fit.axis[a], coeffs[a]), 1e-8) << "basis " << int(t.basis) << " case " << t.basis_case << " axis " << a;
      EXPECT_LT(fit.axis[a].residual_rms, 1e-11);
    }
    // Stored as float: the error a decoder sees is float rounding, not fit error.
    EXPECT_LT(fit.max_error, 1e-5);
  }
}

TEST(FitCore, SearchFindsTheGeneratingCaseAndParameters) {
  std::mt19937 rng(11);
  const Truth cases[] = {{Basis::Pde8, 2, 3.25, 5.5}, {Basis::Pde8, 1, 1.5, 9.0}, {Basis::Pde32, 0, 2.5, 6.0}};
  for (const Truth& t : cases) {
    std::vector<double> coeffs[3];
    CurveFrames curve = curve_from_truth(t, rng, 40, 9, coeffs);
    FitOptions o;
    o.basis = t.basis;
    o.refined_cases = 4;
    CurveFit fit;
    std::string error;
    ASSERT_TRUE(fit_curve(curve, o, &fit, &error)) << error;
    for (int a = 0; a < 3; ++a) {
      const CurveMotion& m = fit.axis[a].motion;
      EXPECT_EQ(m.basis_case, t.basis_case) << a;
      EXPECT_NEAR(m.time_param, t.time_param, 1e-5) << a;
      EXPECT_NEAR(m.space_param, t.space_param, 1e-5) << a;
      if (m.time_param == float(t.time_param) && m.space_param == float(t.space_param)) {
        EXPECT_LT(coeff_error(curve, fit.axis[a], coeffs[a]), 1e-8) << int(t.basis) << " axis " << a;
      }
      EXPECT_LT(fit.axis[a].residual_rms, 1e-6) << a;
    }
  }
}

// Least squares with the monomials u^j tau^i (j <= 3, i <= 1): the "cubic in u x linear in t"
// fit of the same size, built independently of codec/basis.
double polynomial_rms(const CurveFrames& c, int axis) {
  const size_t P = c.points(), F = c.frames();
  Eigen::MatrixXd a(Eigen::Index(P * F), 8);
  Eigen::VectorXd y(Eigen::Index(P * F));
  for (size_t f = 0; f < F; ++f)
    for (size_t p = 0; p < P; ++p) {
      Eigen::Index row = Eigen::Index(f * P + p);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 4; ++j) a(row, i * 4 + j) = std::pow(c.tau[f], i) * std::pow(c.u[p], j);
      y(row) = c.xyz[(f * P + p) * 3 + size_t(axis)];
    }
  Eigen::VectorXd r = y - a * a.colPivHouseholderQr().solve(y);
  return std::sqrt(r.squaredNorm() / double(P * F));
}

TEST(FitCore, NeverWorseThanTheSameSizePolynomial) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 12; ++trial) {
    double k[3][6];
    for (auto& row : k)
      for (double& v : row) v = d(rng);
    CurveFrames curve = make_curve(25, 2 + size_t(trial % 5), [&](int a, double tau, double u) {
      const double* q = k[a];
      return q[0] * u + 0.3 * std::sin(3 * q[1] * u + 2 * q[2] * tau) + 0.2 * q[3] * std::cos(4 * u * (1 + q[4] * tau)) +
             0.1 * q[5] * tau * tau;
    });
    FitOptions o;
    CurveFit fit;
    std::string error;
    ASSERT_TRUE(fit_curve(curve, o, &fit, &error)) << error;
    for (int a = 0; a < 3; ++a) {
      double poly = polynomial_rms(curve, a);
      EXPECT_LE(fit.axis[a].residual_rms, poly * (1 + 1e-9) + 1e-14) << "trial " << trial << " axis " << a;
    }
  }
}

// Rotation about `axis` by `angle` (radians), row-major.
void rotation(const double axis[3], double angle, double r[9]) {
  Eigen::Matrix3d m = Eigen::AngleAxisd(angle, Eigen::Vector3d(axis[0], axis[1], axis[2]).normalized()).toRotationMatrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r[i * 3 + j] = m(i, j);
}

TEST(FitCore, RigidRemovalRecoversAKnownRotationAndRestoresInBetween) {
  // A cubic space curve (exactly representable at parameter 0) turning at constant angular
  // speed about a fixed axis while its centroid moves on a line: slerp + linear centroid
  // reproduce the frames between the keys exactly.
  const double axis[3] = {0.3, -0.5, 0.8};
  const double shift[3] = {0.4, 0.1, -0.7};
  const size_t P = 20, F = 9;
  auto raw_shape = [](int a, double u) { return a == 0 ? u : a == 1 ? 0.5 * u * u - 0.1 : 0.3 * u * u * u + 0.2 * u; };
  double mean[3] = {0, 0, 0};  // centred, so the rotation is about the centroid
  for (size_t p = 0; p < P; ++p)
    for (int a = 0; a < 3; ++a) mean[a] += raw_shape(a, double(p) / double(P - 1)) / double(P);
  auto shape = [&](int a, double u) { return raw_shape(a, u) - mean[a]; };
  auto world = [&](double tau, double u, double out[3]) {
    double r[9], s[3];
    rotation(axis, 1.2 * tau, r);
    for (int a = 0; a < 3; ++a) s[a] = shape(a, u);
    for (int a = 0; a < 3; ++a) out[a] = r[a * 3] * s[0] + r[a * 3 + 1] * s[1] + r[a * 3 + 2] * s[2] + shift[a] * tau;
  };
  CurveFrames all = make_curve(P, F, [&](int a, double tau, double u) {
    double x[3];
    world(tau, u, x);
    return x[a];
  });
  // Fit every other frame, as the 2024 protocol does.
  CurveFrames even;
  even.u = all.u;
  for (size_t f = 0; f < F; f += 2) {
    even.tau.push_back(all.tau[f]);
    even.xyz.insert(even.xyz.end(), all.xyz.begin() + long(f * P * 3), all.xyz.begin() + long((f + 1) * P * 3));
  }
  FitOptions o;
  o.remove_rigid = true;
  o.fixed_time_param = 0;
  o.fixed_space_param = 0;
  CurveFit fit;
  std::string error;
  ASSERT_TRUE(fit_curve(even, o, &fit, &error)) << error;
  ASSERT_EQ(fit.rigid.keys.size(), even.frames());
  for (size_t k = 0; k < fit.rigid.keys.size(); ++k) {
    double got[9], c[3], want[9];
    rigid_at(fit.rigid, fit.rigid.keys[k].tau, got, c);
    rotation(axis, 1.2 * fit.rigid.keys[k].tau, want);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(got[i], want[i], 1e-10) << "key " << k;
  }
  EXPECT_LT(fit.max_error, 1e-5);
  std::vector<double> xyz(P * 3);
  for (size_t f = 1; f < F; f += 2) {
    evaluate_curve_fit(fit, all.u, {}, all.tau[f], xyz.data());
    for (size_t k = 0; k < P * 3; ++k) EXPECT_NEAR(xyz[k], all.xyz[f * P * 3 + k], 1e-5) << "frame " << f;
  }
}

TEST(FitCore, KabschNeverReturnsAReflection) {
  // The second frame is the first mirrored: the best orthogonal map is a reflection; the
  // rotation must still have det +1.
  CurveFrames c = make_curve(12, 2, [](int a, double tau, double u) {
    double base[3] = {u, std::sin(3 * u), 0.2 * u * u};
    return (a == 0 && tau > 0.5) ? -base[0] : base[a];
  });
  RigidTrack track;
  std::vector<double> local;
  remove_rigid_motion(c.xyz, c.tau, c.points(), &track, &local);
  double r[9], cen[3];
  rigid_at(track, 1.0, r, cen);
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> m(r);
  EXPECT_NEAR(m.determinant(), 1.0, 1e-12);
  EXPECT_LT((m * m.transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(FitCore, DisplacementModeFitsPositionsMinusRest) {
  std::mt19937 rng(5);
  std::vector<double> coeffs[3];
  for (auto& c : coeffs) c = random_coeffs(rng, 8);
  auto rest_shape = [](int a, double u) { return std::sin(5 * u + a) + 2 * u * u * u * u; };  // not in the basis
  CurveFrames c = make_curve(30, 5, [&](int a, double tau, double u) {
    return rest_shape(a, u) + tau * motion_value(Basis::Pde8, 2, 2.0, 3.0, coeffs[a], tau, u);
  });
  for (size_t p = 0; p < c.points(); ++p)
    for (int a = 0; a < 3; ++a) c.rest.push_back(c.xyz[p * 3 + size_t(a)]);  // frame 0 is the rest pose
  FitOptions o;
  o.mode = FitMode::Displacement;
  CurveFit disp, absolute;
  std::string error;
  ASSERT_TRUE(fit_curve(c, o, &disp, &error)) << error;
  o.mode = FitMode::Absolute;
  ASSERT_TRUE(fit_curve(c, o, &absolute, &error)) << error;
  EXPECT_LT(disp.rms_error, 0.5 * absolute.rms_error);
  o.mode = FitMode::Displacement;
  c.rest.pop_back();
  EXPECT_FALSE(fit_curve(c, o, &disp, &error));
  EXPECT_NE(error.find("rest"), std::string::npos);
}

TEST(FitCore, ResultsDoNotDependOnThreadCount) {
  std::vector<CurveFrames> curves;
  for (int i = 0; i < 7; ++i)
    curves.push_back(make_curve(15 + size_t(i), 4, [i](int a, double tau, double u) {
      return std::sin((2 + i) * u + a) * (1 + tau * tau) + 0.1 * i * tau;
    }));
  FitOptions o;
  std::vector<CurveFit> one, three;
  std::string error;
  ASSERT_TRUE(fit_curves(curves, o, 1, &one, &error)) << error;
  ASSERT_TRUE(fit_curves(curves, o, 3, &three, &error)) << error;
  ASSERT_EQ(one.size(), three.size());
  for (size_t i = 0; i < one.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(one[i].axis[a].motion.coeffs, three[i].axis[a].motion.coeffs);
      EXPECT_EQ(one[i].axis[a].motion.time_param, three[i].axis[a].motion.time_param);
      EXPECT_EQ(one[i].axis[a].motion.basis_case, three[i].axis[a].motion.basis_case);
    }
}

TEST(FitCore, TinyCurvesAndSingleFramesAreFittedExactly) {
  // Fewer points or frames than functions: the minimum-norm solution interpolates.
  for (size_t points : {1, 2, 3})
    for (size_t frames : {1, 2})
      for (Basis b : {Basis::Pde8, Basis::Pde32}) {
        CurveFrames c = make_curve(std::max<size_t>(points, 2), frames, [](int a, double tau, double u) {
          return std::sin(3 * u + a) + tau;
        });
        if (points == 1) {  // one point at u = 0.4
          c.u = {0.4};
          std::vector<double> xyz;
          for (size_t f = 0; f < frames; ++f) xyz.insert(xyz.end(), c.xyz.begin() + long(f * 6), c.xyz.begin() + long(f * 6 + 3));
          c.xyz = xyz;
        }
        FitOptions o;
        o.basis = b;
        CurveFit fit;
        std::string error;
        ASSERT_TRUE(fit_curve(c, o, &fit, &error)) << error;
        EXPECT_LT(fit.max_error, 1e-5) << points << " points, " << frames << " frames, basis " << int(b);
      }
}

TEST(FitCore, StoredFitNeverLosesToThePolynomialLimitInFloat) {
  // Eight points and eight space functions: the search can reach a near-zero double residual
  // at large r whose coefficients do not survive float storage (seen on chicken-crossing).
  // The stored error must never exceed that of the float polynomial limit.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> d(-1, 1);
  for (int trial = 0; trial < 20; ++trial) {
    double k[3][4];
    for (auto& row : k)
      for (double& v : row) v = d(rng);
    CurveFrames c = make_curve(8, 6, [&](int a, double tau, double u) {
      return 10 + k[a][0] * std::sin(7 * u + k[a][1]) + 0.3 * k[a][2] * std::cos(11 * u * u + tau) + k[a][3] * tau;
    });
    FitOptions o;
    o.basis = Basis::Pde32;
    o.remove_rigid = trial % 2 == 1;
    CurveFit searched, polynomial;
    std::string error;
    ASSERT_TRUE(fit_curve(c, o, &searched, &error)) << error;
    o.fixed_time_param = 0;
    o.fixed_space_param = 0;
    ASSERT_TRUE(fit_curve(c, o, &polynomial, &error)) << error;
    EXPECT_LE(searched.rms_error, polynomial.rms_error * (1 + 1e-6) + 1e-9) << "trial " << trial;
  }
}

// Leaving a fitted frame out: zero at the generating parameters (each frame is predicted
// exactly by the others), positive at a wrong alpha, and the search keeps the generating
// alpha though its range reaches far beyond it.
TEST(FitCore, LeaveOneOutKeepsTheGeneratingTimeParameter) {
  std::mt19937 rng(5);
  const Truth t{Basis::Pde32, 0, 2.5, 6.0};
  std::vector<double> coeffs[3];
  const CurveFrames curve = curve_from_truth(t, rng, 40, 6, coeffs);
  const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(curve.u.data(), Eigen::Index(curve.u.size()));
  const Eigen::VectorXd tau = Eigen::Map<const Eigen::VectorXd>(curve.tau.data(), Eigen::Index(curve.tau.size()));
  Eigen::MatrixXd w(Eigen::Index(curve.points()), Eigen::Index(curve.frames()));
  for (size_t f = 0; f < curve.frames(); ++f)
    for (size_t p = 0; p < curve.points(); ++p) w(Eigen::Index(p), Eigen::Index(f)) = curve.xyz[(f * curve.points() + p) * 3];
  const double scale = w.squaredNorm();
  EXPECT_LT(leave_out_error2(w, u, tau, t.basis, 0, t.time_param, t.space_param), 1e-16 * scale);
  EXPECT_GT(leave_out_error2(w, u, tau, t.basis, 0, 20.0, t.space_param), 1e-6 * scale);
  EXPECT_EQ(leave_out_error2(w.leftCols(2), u, tau.head(2), t.basis, 0, t.time_param, t.space_param),
            std::numeric_limits<double>::infinity());
  FitOptions o;
  o.basis = t.basis;
  o.max_time_param = 30;
  o.time_param_by_leave_out = true;
  CurveFit fit;
  std::string error;
  ASSERT_TRUE(fit_curve(curve, o, &fit, &error)) << error;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(fit.axis[a].motion.time_param, t.time_param, 1e-4) << a;
}

TEST(FitCore, RejectsBadInput) {
  CurveFrames c = make_curve(5, 3, [](int, double tau, double u) { return u + tau; });
  FitOptions o;
  CurveFit fit;
  std::string error;
  CurveFrames bad = c;
  std::swap(bad.tau[0], bad.tau[1]);
  EXPECT_FALSE(fit_curve(bad, o, &fit, &error));
  EXPECT_NE(error.find("increasing"), std::string::npos);
  bad = c;
  bad.xyz[4] = std::nan("");
  EXPECT_FALSE(fit_curve(bad, o, &fit, &error));
  bad = c;
  bad.xyz.pop_back();
  EXPECT_FALSE(fit_curve(bad, o, &fit, &error));
  o.fixed_case = 2;
  o.basis = Basis::Pde32;
  EXPECT_FALSE(fit_curve(c, o, &fit, &error));
}

}  // namespace
}  // namespace dcurve
