// Reads a mesh file's vertices and polygons exactly as stored, through OpenMesh's readers (OFF,
// PLY, text and binary; OBJ has its own reader, obj_reader.h, since OpenMesh's opens the files
// an OBJ's mtllib names) but without OpenMesh's mesh kernel: the kernel cannot
// hold a non-manifold edge and its importer duplicates the vertices of such a face, so
// vertex i read would no longer be vertex i in the file.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

struct PolygonSoup {
  std::vector<float> xyz;                 // 3 per vertex, in file order
  std::vector<uint32_t> polygon_offsets;  // polygon p's ids: ids[offsets[p] .. offsets[p + 1])
  std::vector<uint32_t> ids;              // vertex ids as the reader passed them
  size_t polygon_count() const { return polygon_offsets.empty() ? 0 : polygon_offsets.size() - 1; }
};

// False when OpenMesh cannot read the file ("PATH: cannot read mesh ...").
bool read_polygon_soup(const std::string& path, PolygonSoup* soup, std::string* error);

}  // namespace dcurve
