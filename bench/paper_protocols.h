// The two papers' evaluation protocols, runnable on any animation and curve partition.
//
// "paper2024" (2024 paper, sec. 5, Table 1): frames 0, 2, ..., 10 are fitted, 1, 3, ..., 9
//   predicted (tau = n / 10). PDE: the 32-term basis fitted per curve after rigid-motion removal
//   (time parameter searched up to pi / (2 * 0.2), where six samples 0.2 apart stop aliasing)
//   (Kabsch, restored between fitted frames by slerp + linear centroid), stored as float and
//   evaluated through codec/basis. Baseline: a least-squares cubic B-spline with 50 control
//   points per curve and frame (fewer when the curve has fewer points), linearly interpolated
//   between fitted frames. Per frame n: E_An = mean over curves of (mean point distance / D),
//   E_Mn = max over curves of (max point distance / D), D = the distance between the curve's two
//   furthest points at frame n (eqs. (26)-(27)). Summary over n = 0..10: mean E_An, max E_Mn.
// "paper2022" (2022 paper, sec. 5.1, Tables 2-3): two keyframes far apart (20 and 100 when the
//   animation has them, else the first and last), one 8-term fit per curve (tau 0 and 1) versus
//   two cubic Bezier and two cubic B-spline fits (4 control points each). E_A / E_M of eq. (23):
//   mean / max over points of |error| / |original point| (distance from the origin, as the paper
//   defines it), averaged / maximized over both keyframes and all curves; fit time in ms on one
//   thread.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "codec/common/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

// Runs "paper2024" or "paper2022" on an animation with a given curve partition; returns the JSON result; prints a table to `table` when non-null.
// alpha_searches (paper2024): also fits with the former time-parameter search (least squares
// up to 30) and with the leave-one-out choice, and reports their alpha and errors (three
// more fits of every curve).
bool run_paper_protocol(const std::string& protocol, const Animation& anim, const Curves& curves, nlohmann::json* result,
                        std::string* table, std::string* error, bool alpha_searches = false);

// Rows of `columns` consecutive vertices (a row-major grid such as cloth-sphere's 50 x 50
// sheet), u by chord length on frame 0. Fails unless vertex_count is a multiple of columns.
bool grid_row_curves(const Animation& anim, uint32_t columns, Curves* curves, std::string* error);

}  // namespace dcurve
