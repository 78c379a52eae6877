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

// What an OBJ carries besides positions (a file's render vertices, codec/common/render_mesh.h).
struct ObjRender {
  std::vector<uint32_t> source;             // per render vertex: its vertex
  std::vector<uint32_t> corners;            // render ids, 3 per triangle, group after group
  std::vector<float> uv;                    // 2 per render vertex (glTF's v), or empty
  std::vector<uint32_t> group_faces;        // triangles per group; empty: one group, no usemtl
  std::vector<std::string> group_names;     // usemtl names ("" writes none)
  std::string material_library;             // mtllib, or ""
  bool empty() const { return source.empty(); }
};

// An OBJ with `mtllib`, one `v` per vertex (vertex i stays vertex i), a `vt` and (with
// `normals`, one per render vertex) a `vn` per render vertex, and faces `v/vt/vn` by group.
// Control characters in the names are written as \xNN, so each name stays on its line.
void obj_render_bytes(const float* xyz, uint32_t vertex_count, const ObjRender& render, const float* normals,
                      std::string* bytes);

}  // namespace dcurve
