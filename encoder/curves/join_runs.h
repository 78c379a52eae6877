// Local repairs of a linked path set after the greedy passes: runs whose ends found no free
// neighbour are joined by re-routing one interior link, and vertices left alone are threaded
// into a neighbouring link.
#pragma once
#include <cstdint>
#include <vector>

#include "encoder/curves/link_paths.h"
#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace curves_detail {

// Joins two runs through a third: for a run end a next to an interior vertex x of another run
// (links x-y, x-z), links a-x, drops x-y and links y to a free neighbour b of y, so one run
// fewer remains. Among the possible moves of an end, the one adding the least bend
// (sum of 1 - cos over the turns it creates minus those it removes) is taken if that is below
// `max_added_bend`. `sweeps` passes over the vertices in id order (deterministic).
void join_runs_through_neighbours(const SurfaceGraph& graph, const std::vector<float>& xyz, double max_added_bend,
                                  uint32_t sweeps, PathLinks* links);

// A vertex with no link joins a curve through one of its triangles: if two of its neighbours
// are linked to each other, a-b becomes a-s-b (shortest detour wins, ties to smaller ids).
void thread_lonely_vertices(const SurfaceGraph& graph, const std::vector<float>& xyz, PathLinks* links);

}  // namespace curves_detail
}  // namespace dcurve
