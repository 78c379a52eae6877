#include "bench/paper_splines.h"

#include <Eigen/Dense>
#include <algorithm>

namespace dcurve {
namespace {

// Cox-de Boor: all basis functions of `degree` on `knots` at x; the right end x = 1 belongs
// to the last span so the curve interpolates its last control point.
void bspline_row(const std::vector<double>& knots, int degree, int n, double x, double* row) {
  std::vector<double> N(knots.size() - 1, 0.0);
  size_t span = size_t(degree);
  while (span + 1 < size_t(n) && x >= knots[span + 1]) ++span;
  N[span] = 1.0;
  for (int d = 1; d <= degree; ++d)
    for (size_t i = 0; i + size_t(d) < knots.size() - 1; ++i) {
      double left = 0, right = 0;
      double dl = knots[i + size_t(d)] - knots[i], dr = knots[i + size_t(d) + 1] - knots[i + 1];
      if (dl > 0) left = (x - knots[i]) / dl * N[i];
      if (dr > 0) right = (knots[i + size_t(d) + 1] - x) / dr * N[i + 1];
      N[i] = left + right;
    }
  for (int i = 0; i < n; ++i) row[i] = N[size_t(i)];
}

// Rows of the clamped uniform B-spline basis with n control points (degree min(3, n - 1)) at u.
Eigen::MatrixXd bspline_design(const std::vector<double>& u, int n) {
  const int degree = std::min(3, n - 1);
  std::vector<double> knots;
  for (int i = 0; i <= degree; ++i) knots.push_back(0.0);
  const int interior = n - degree - 1;
  for (int i = 1; i <= interior; ++i) knots.push_back(double(i) / (interior + 1));
  for (int i = 0; i <= degree; ++i) knots.push_back(1.0);
  Eigen::MatrixXd a(Eigen::Index(u.size()), n);
  std::vector<double> row(static_cast<size_t>(n));
  for (size_t p = 0; p < u.size(); ++p) {
    bspline_row(knots, degree, n, u[p], row.data());
    for (int i = 0; i < n; ++i) a(Eigen::Index(p), i) = row[size_t(i)];
  }
  return a;
}

Eigen::MatrixXd points_matrix(const double* xyz, size_t points) {
  Eigen::MatrixXd y(Eigen::Index(points), 3);
  for (size_t p = 0; p < points; ++p)
    for (int k = 0; k < 3; ++k) y(Eigen::Index(p), k) = xyz[p * 3 + size_t(k)];
  return y;
}

void store(const Eigen::MatrixXd& m, std::vector<double>* out) {
  out->resize(size_t(m.rows()) * 3);
  for (Eigen::Index p = 0; p < m.rows(); ++p)
    for (int k = 0; k < 3; ++k) (*out)[size_t(p * 3 + k)] = m(p, k);
}

void least_squares(const Eigen::MatrixXd& a, const std::vector<double>& u, const double* xyz,
                   std::vector<double>* fitted) {
  store(a * a.colPivHouseholderQr().solve(points_matrix(xyz, u.size())), fitted);
}

int control_count(int control_points, size_t points) { return std::max(1, std::min(control_points, int(points))); }

}  // namespace

void fit_bspline(const std::vector<double>& u, const double* xyz, int control_points, std::vector<double>* fitted) {
  least_squares(bspline_design(u, control_count(control_points, u.size())), u, xyz, fitted);
}

void fit_bspline_controls(const std::vector<double>& u, const double* xyz, int control_points,
                          std::vector<double>* controls) {
  const Eigen::MatrixXd a = bspline_design(u, control_count(control_points, u.size()));
  store(a.colPivHouseholderQr().solve(points_matrix(xyz, u.size())), controls);
}

void evaluate_bspline(const std::vector<double>& controls, const std::vector<double>& u, std::vector<double>* xyz) {
  const size_t n = controls.size() / 3;
  store(bspline_design(u, int(n)) * points_matrix(controls.data(), n), xyz);
}

void fit_bezier(const std::vector<double>& u, const double* xyz, std::vector<double>* fitted) {
  const Eigen::Index P = Eigen::Index(u.size());
  Eigen::MatrixXd a(P, 4);
  for (Eigen::Index p = 0; p < P; ++p) {
    double x = u[size_t(p)], y = 1 - x;
    a(p, 0) = y * y * y;
    a(p, 1) = 3 * x * y * y;
    a(p, 2) = 3 * x * x * y;
    a(p, 3) = x * x * x;
  }
  least_squares(a, u, xyz, fitted);
}

}  // namespace dcurve
