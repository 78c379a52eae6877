// The bytes of one mesh file (.obj, .off or binary .ply), vertices and triangles exactly as
// given: coordinates as the shortest text that reads back to the same float (OBJ, OFF) or
// the floats themselves (PLY), and any face list, non-manifold ones included (OpenMesh's
// writers go through its mesh kernel, which cannot hold those).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// `extension` as lowercase_extension gives it; false for one other than .obj, .off, .ply.
bool mesh_file_bytes(const std::string& extension, const float* xyz, uint32_t vertex_count,
                     const std::vector<uint32_t>& faces, std::string* bytes);

}  // namespace dcurve
