// Links mesh edges into vertex-disjoint paths and cycles (a linear forest) that follow a
// direction field, then reads the paths off as curves.
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"
#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace curves_detail {

constexpr uint32_t kNoVertex = UINT32_MAX;

// One sweep over the edges (best aligned first). Later passes accept sharper turns, so a run
// first grows as straight as it can and only then is joined to its neighbours around a bend;
// the cut to the target length (cut_to_target.h) then cuts at those bends where they cost
// more than a new curve.
struct LinkPass {
  double max_turn_deg;     // largest turn a new link may create at either end
  uint32_t short_points;   // > 0: one of the two runs must have fewer points than this
  bool may_close;          // whether a link may close a run into a cycle
};

struct LinkParams {
  std::vector<LinkPass> passes = {
      {45.0, 0, true},    // straight runs
      {70.0, 0, true},    // gentle bends are worth less than a new curve
      {135.0, 4, false},  // absorb short runs (fewer than 4 points) even around a sharp bend
      {180.0, 0, false},  // hairpins between parallel runs: cut there first if too long
  };
  uint32_t join_sweeps = 2;     // passes of join_runs_through_neighbours (0 = none)
  // Its limit on added bend, in 1 - cos units. extract_curves sets 1 / bend_weight: a join is
  // made only when its bends cost less than the curve it saves.
  double max_join_bend = 2.0;
};

// Two neighbours per vertex (kNoVertex when unused); a vertex with two is inside a curve.
struct PathLinks {
  std::vector<uint32_t> nbr;  // vertex_count * 2
};

// Greedy: edges best aligned with `dir` (vertex_count * 3) are linked first; a link is taken
// when both ends have a free slot, the turn it makes stays under the pass's limit, and it does
// not close a cycle (of at least 3 vertices) unless the pass allows it. Then runs are joined
// and lone vertices threaded in (join_runs.h). Deterministic (ties broken by edge order).
PathLinks link_along_field(const SurfaceGraph& graph, const std::vector<float>& xyz,
                           const std::vector<float>& dir, const LinkParams& params);

// Reads the linked paths in order: open ones start at their end with the smaller vertex id and
// are listed by that id; cycles start at their smallest id. Fills vertices/offsets/closed of
// *out (u left empty).
void assemble_paths(const PathLinks& links, Curves* out);

// Cosine of the turn at `b` for the step a -> b -> c, in [-1, 1]; 1 when a step has zero length.
double turn_cosine(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c);

// Turning angle in radians at `b` for the step a -> b -> c; 0 when straight or degenerate.
double turn_angle(const std::vector<float>& xyz, uint32_t a, uint32_t b, uint32_t c);

}  // namespace curves_detail
}  // namespace dcurve
