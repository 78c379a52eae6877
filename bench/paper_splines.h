// The papers' static baselines: least-squares cubic Bezier (2022 eq. (17)) and cubic B-spline
// curves (2022 eq. (19); 2024 Table 1 with 50 control points), fitted at given parameters u.
#pragma once
#include <vector>

namespace dcurve {

// Least-squares clamped uniform B-spline of degree min(3, n - 1) with n = min(control_points,
// points) control points, fitted to points (u in [0, 1], xyz points * 3). Writes the fitted
// positions at the same u (points * 3). With 4 control points it is the cubic Bezier curve.
void fit_bspline(const std::vector<double>& u, const double* xyz, int control_points, std::vector<double>* fitted);

// The same fit's control points (n * 3, n as above), and the curve of control points
// `controls` (n * 3) evaluated at u (points * 3): what the 2024 paper interpolates in time.
void fit_bspline_controls(const std::vector<double>& u, const double* xyz, int control_points,
                          std::vector<double>* controls);
void evaluate_bspline(const std::vector<double>& controls, const std::vector<double>& u, std::vector<double>* xyz);

// Least-squares cubic Bezier curve (4 control points, Bernstein basis), fitted positions at u.
void fit_bezier(const std::vector<double>& u, const double* xyz, std::vector<double>* fitted);

}  // namespace dcurve
