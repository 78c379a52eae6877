// Checks OFF and PLY files before OpenMesh reads them, and says how many vertices and faces
// each declares. OpenMesh's text readers do not fail on a value they cannot parse: the OFF and
// ASCII PLY readers stop reading numbers and fill the rest with zeros, and every reader skips
// a face it cannot use. Comparing what was read with what the file declares catches all of it.
// (OBJ is parsed by dcurve itself: encoder/io/obj_reader.h.)
#pragma once
#include <cstdint>
#include <string>

namespace dcurve {

struct DeclaredCounts {
  int64_t vertices = -1;  // -1: the file does not say (not OFF or PLY)
  int64_t faces = -1;     // polygons: the header's count
};

// For .off (text; every variant: COFF, NOFF, STOFF, ...) and .ply files: a PLY header must be
// well formed, with x, y, z vertex properties; every vertex record's coordinates must be
// decimal numbers within float range (three for OFF, every property of the PLY vertex
// element); every face record of OFF and ASCII PLY must hold 3 or more vertex ids in range.
// False with "PATH: line N: ..." otherwise.
// Binary PLY values reach the finite check after reading; binary OFF is refused.
bool check_text_mesh_vertices(const std::string& path, DeclaredCounts* declared, std::string* error);

}  // namespace dcurve
