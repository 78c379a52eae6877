// Procedural closed triangle surfaces for the built-in scenes. Units are metres; every
// surface is closed, 2-manifold and outward-oriented, so TetGen can fill it with tets.
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace dcurve::corpus {

struct SurfaceMesh {
  std::vector<double> xyz;       // 3 coordinates per vertex, metres
  std::vector<uint32_t> faces;   // 3 vertex ids per triangle, counter-clockwise seen from outside
};

// Axis-aligned box of size (sx, sy, sz) > 0 centred at the origin, each side split into a
// regular grid of (nx, ny, nz) >= 1 cells. Vertex count 2(nx ny + ny nz + nz nx) + 2.
SurfaceMesh box_surface(double sx, double sy, double sz, int nx, int ny, int nz);

// Sphere of `radius` > 0 at the origin: a box grid with `divisions` >= 1 cells per side,
// projected onto the sphere (no pole singularities).
SurfaceMesh sphere_surface(double radius, int divisions);

// Thick-walled tube along +y from y = 0 to y = length > 0, radii 0 < inner < outer,
// `around` >= 3 segments around and `along` >= 1 segments along, closed by annular caps.
SurfaceMesh tube_surface(double inner_radius, double outer_radius, double length, int around, int along);

// Builds a surface from a JSON spec {"generator": "box"|"sphere"|"tube", ...}; see the
// README's scene-file section for the keys. Returns false with a message on a bad spec.
bool generate_surface(const nlohmann::json& spec, SurfaceMesh* out, std::string* error);

}  // namespace dcurve::corpus
