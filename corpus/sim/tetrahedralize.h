// Fills a closed triangle surface with tetrahedra through the TetGen library, keeping the
// surface exactly (TetGen -Y: no Steiner points on the boundary), so the input surface
// vertices are the first points of the tet mesh, in their input order.
#pragma once
#include <Eigen/Core>

#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

struct TetMesh {
  std::vector<Eigen::Vector3d> points;  // metres; [0, surface_vertex_count) = the input surface vertices
  std::vector<Eigen::Vector4i> tets;    // 4 point ids each, positively oriented (det > 0)
  uint32_t surface_vertex_count = 0;
};

struct TetOptions {
  double quality = 2.0;    // max radius-edge ratio (TetGen -q), >= 1.1, 0 = no quality refinement
  double max_volume = 0;   // max tet volume in m^3 (TetGen -a), 0 = unlimited
};

// Checks that a surface can be tetrahedralized: finite coordinates, indices in range, no
// degenerate (zero-area) triangle, every vertex used, and closed and consistently oriented
// (every edge shared by exactly two triangles in opposite directions).
bool check_closed_surface(const std::vector<double>& xyz, const std::vector<uint32_t>& faces, std::string* error);

// Tetrahedralizes a surface (3 doubles per vertex, 3 ids per triangle). False with a
// message when the surface fails check_closed_surface or TetGen rejects it (for example
// self-intersections). Deterministic: TetGen uses a fixed random seed.
bool tetrahedralize_surface(const std::vector<double>& xyz, const std::vector<uint32_t>& faces,
                            const TetOptions& options, TetMesh* out, std::string* error);

}  // namespace dcurve
