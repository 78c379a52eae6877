// Candidate tangent direction fields that curves may follow. Curve extraction links mesh
// edges along each candidate and keeps, per connected component, the one whose curves come
// out longest and straightest; no single field suits a sheet, a tube and a horse alike.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace curves_detail {

struct DirectionField {
  std::string name;        // e.g. "axis0-along", "geodesic-across"; for diagnostics
  std::vector<float> dir;  // vertex_count * 3: tangent direction, length in [0, 1] = confidence
};

// Per component: the height functions along its principal axes (and the two diagonals of the
// first two axes), and the edge-length geodesic distance from its extreme vertex along the
// first axis. For each scalar, one field follows its gradient ("along") and one its
// iso-lines ("across"). Every field is zero on isolated vertices.
std::vector<DirectionField> candidate_fields(const SurfaceGraph& graph, const std::vector<float>& xyz,
                                             const std::vector<uint32_t>& faces);

}  // namespace curves_detail
}  // namespace dcurve
