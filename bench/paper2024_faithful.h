// The 2024 paper's protocol as its text describes it (sec. 4.3-5, Table 1), beside the
// honest held-out protocol of paper_protocols.h:
// - curves: full-length lines (surface_lines: one per surface line of a body lying along an
//   axis, such as the built-in rope; the paper's cube-rope has 24 lines of 832 points);
// - alignment of EVERY frame 0..10 to frame 0 (eq. 19: shift by the first point's motion;
//   eqs. 20-23: an unconstrained 3 x 3 least-squares map onto frame 0), and errors measured
//   in that aligned frame, so the odd frames are aligned with their own truth;
// - u per frame by eq. 24: the normalized coordinate along the line's axis;
// - the 32-term basis fitted on frames 0, 2, ..., 10 at those u (eq. 25), one (alpha, r) per
//   curve by a grid search with alpha <= pi / (2 dt) (dt = 0.2, the fitted frames' spacing:
//   above it the time functions alias on six samples);
// - per even frame a least-squares cubic B-spline with 50 control points at the same u, its
//   control points interpolated linearly for the odd frames;
// - eqs. 26-27 with the paper's D: the distance between the two furthest points of the first
//   curve (at frame 0).
#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "codec/common/model.h"
#include "encoder/io/frames.h"

namespace dcurve {

// Lines of vertices that share their two other coordinates at frame 0 (within 1e-6 L),
// along the axis of frame 0's largest extent, ordered along it; lines of fewer than 11
// points are dropped (u is set by chord length, unused by the faithful protocol). False when
// no line is left.
bool surface_lines(const Animation& anim, Curves* lines, std::string* error);

// Runs the faithful protocol; *table gets the per-frame table and the summaries.
// alpha_searches: also the former search (least squares, alpha <= 30) and the leave-one-out
// choice (alpha <= 30 and within the cap), each with its alpha and errors.
bool run_paper2024_faithful(const Animation& anim, const Curves& curves, nlohmann::json* result, std::string* table,
                            std::string* error, bool alpha_searches = false);

}  // namespace dcurve
