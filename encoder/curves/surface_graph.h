// The mesh topology curve extraction needs, built once through OpenMesh and then held in
// flat arrays so that the many linking passes stay cache-friendly.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {
namespace curves_detail {

struct SurfaceGraph {
  uint32_t vertex_count = 0;
  std::vector<std::array<uint32_t, 2>> edges;  // each mesh edge once, smaller id first, sorted
  std::vector<uint32_t> adj_offsets;           // CSR: neighbours of v are adj[adj_offsets[v] ..)
  std::vector<uint32_t> adj;                   // sorted ascending per vertex
  std::vector<float> normals;                  // vertex_count * 3, unit; zero for isolated vertices
  std::vector<uint32_t> component;             // per vertex, 0 .. component_count-1 in vertex order
  uint32_t component_count = 0;

  bool adjacent(uint32_t a, uint32_t b) const;
};

// Fails (false + message) on out-of-range or repeated ids in a face, a size not a multiple of
// 3, wrong xyz size, non-finite coordinates, or a face OpenMesh rejects as non-manifold.
bool build_surface_graph(const std::vector<float>& xyz, uint32_t vertex_count,
                         const std::vector<uint32_t>& faces, SurfaceGraph* graph,
                         std::string* error);

}  // namespace curves_detail
}  // namespace dcurve
