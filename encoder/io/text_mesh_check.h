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
  int64_t vertices = -1;  // -1: the file does not say (binary OFF)
  int64_t faces = -1;     // polygons: "f" lines in OBJ, the header's count in OFF and PLY
};

// For .obj, .off (every variant: COFF, NOFF, STOFF, ...) and ASCII .ply files: every vertex
// record's coordinates must be decimal numbers within float range (three coordinates for
// OBJ and OFF, every property of the PLY vertex element). False with "PATH: line N: ..."
// otherwise. Binary PLY and OFF values reach the finite check after reading.
bool check_text_mesh_vertices(const std::string& path, DeclaredCounts* declared, std::string* error);

}  // namespace dcurve
