// Cuts linked runs into curves of at most the target length, where cutting pays most.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {
namespace curves_detail {

// What the bend a -> b -> c costs in units of one curve: bend_weight * (1 - cos(turn)); see
// CurveOptions::bend_weight.
double bend_cost(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c, double bend_weight);

// Extra cost of a curve with fewer than 4 points, on top of its 1: short curves carry a whole
// curve's overhead for few points.
constexpr double kShortCurvePenalty = 1.0;

// Splits every run into open pieces of at most `target` (>= 2) points, choosing the cuts that
// minimize sum over pieces of (1 + short penalty + bend costs inside the piece): a run is cut
// at a hairpin even when it fits the target, and long runs are cut at their sharpest bends.
// A closed run that fits stays closed; a longer one is first opened at its sharpest bend.
// u is left empty.
Curves cut_to_target(const Curves& runs, const std::vector<float>& xyz, uint32_t target, double bend_weight);

}  // namespace curves_detail
}  // namespace dcurve
