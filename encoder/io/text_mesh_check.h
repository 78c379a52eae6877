// Checks the vertex records of text mesh files before OpenMesh reads them. OpenMesh's text
// readers do not fail on a coordinate they cannot parse: the OBJ reader skips the line and
// numbers the remaining vertices as if it were absent, the OFF and ASCII PLY readers stop
// reading numbers and fill the rest with zeros. Either way "nan", "inf", "1e999" or a value
// beyond float range would turn into a different mesh, or into a confusing later error.
#pragma once
#include <string>

namespace dcurve {

// For .obj, .off (plain "OFF" header) and ASCII .ply files: every vertex record's values
// must be numbers within float range (three coordinates for OBJ and OFF, every property of
// the PLY vertex element). Other files (binary PLY, OFF variants) pass: their values reach
// the finite check after reading. False with "PATH: line N: ..." otherwise.
bool check_text_mesh_vertices(const std::string& path, std::string* error);

}  // namespace dcurve
