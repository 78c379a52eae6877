// Links mesh edges into vertex-disjoint paths and cycles (a linear forest) that follow a
// direction field, then reads the paths off as curves.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/model.h"
#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace curves_detail {

constexpr uint32_t kNoVertex = UINT32_MAX;

struct LinkParams {
  double straight_turn_deg = 45.0;  // pass 1: any two runs may join when the turn is at most this
  double bent_turn_deg = 70.0;      // pass 2: a join this sharp is still better than two curves
  double short_turn_deg = 110.0;    // pass 3: allowed when one side is a short run
  uint32_t short_points = 4;        // "short run": fewer points than this
};

// Two neighbours per vertex (kNoVertex when unused); a vertex with two is inside a curve.
struct PathLinks {
  std::vector<uint32_t> nbr;  // vertex_count * 2
};

// Greedy: edges best aligned with `dir` (vertex_count * 3) are linked first; a link is taken
// when both ends have a free slot, the turn it makes stays under the pass's limit, and it does
// not close a cycle of fewer than 3 vertices. Vertices still alone afterwards are threaded
// into a linked edge of a triangle they belong to. Deterministic (ties broken by edge order).
PathLinks link_along_field(const SurfaceGraph& graph, const std::vector<float>& xyz,
                           const std::vector<float>& dir, const LinkParams& params);

// Reads the linked paths in order: open ones start at their end with the smaller vertex id and
// are listed by that id; cycles start at their smallest id. Fills vertices/offsets/closed of
// *out (u left empty).
void assemble_paths(const PathLinks& links, Curves* out);

// Turning angle in radians at `b` for the step a -> b -> c; 0 when straight or degenerate.
double turn_angle(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c);

}  // namespace curves_detail
}  // namespace dcurve
