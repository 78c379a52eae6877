// Checks mesh files before OpenMesh reads them, and says how many vertices and faces each
// declares. OpenMesh's text readers do not fail on a value they cannot parse: the OBJ reader
// skips the line and numbers the remaining vertices as if it were absent, the OFF and ASCII
// PLY readers stop reading numbers and fill the rest with zeros; and every reader skips a
// face it cannot use. Comparing what was read with what the file declares catches all of it.
#pragma once
#include <cstdint>
#include <string>

namespace dcurve {

struct DeclaredCounts {
  int64_t vertices = -1;  // -1: the file does not say (not OBJ, OFF or PLY)
  int64_t faces = -1;     // polygons: "f" lines in OBJ, the header's count in OFF and PLY
};

// For .obj, .off (text; every variant: COFF, NOFF, STOFF, ...) and .ply files: a PLY header
// must be well formed, with x, y, z vertex properties; every vertex record's coordinates must
// be decimal numbers within float range (three coordinates for OBJ and OFF, every property of
// the PLY vertex element); every face record of OBJ, OFF and ASCII PLY must hold 3 or more
// vertex ids in range (none twice, for OBJ). False with "PATH: line N: ..." otherwise.
// Binary PLY values reach the finite check after reading; binary OFF is refused.
bool check_text_mesh_vertices(const std::string& path, DeclaredCounts* declared, std::string* error);

}  // namespace dcurve
