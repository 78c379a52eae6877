// What an OBJ's faces say besides positions: each corner's texture coordinate and normal
// (`f v/vt/vn`), each face's material (`usemtl`) and the material library (`mtllib`). OpenMesh
// reads the positions and faces (polygon_reader.h); this reads the rest of the same records,
// so the encoder can keep UVs, normals and material groups (Animation::render).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/animation.h"

namespace dcurve {

// The triangles (fans from each polygon's first corner, as frames.h triangulates) with, per
// corner, its vertex, texture coordinate and normal (-1: none), and per triangle its
// material (index into `materials`, -1 before any usemtl).
struct ObjCorners {
  std::vector<uint32_t> vertex;
  std::vector<int64_t> texcoord, normal;
  std::vector<float> texcoords;  // 2 per vt (u, v as OBJ stores them)
  std::vector<float> normals;    // 3 per vn
  std::vector<int32_t> face_material;
  std::vector<std::string> materials;  // usemtl names, in order of first use
  std::string material_library;        // the first mtllib's file name, "" without
};

// Reads the OBJ at `path` (already read by read_mesh, which checked its records). False with
// a message on an index out of range or malformed corner.
bool read_obj_corners(const std::string& path, ObjCorners* out, std::string* error);

// anim->render (render vertices sorted by vertex, copies in order of first use; UVs flipped
// to glTF's v), groups and material names from `c`, whose triangles must be anim->faces.
// Nothing when the file has neither vt, vn nor usemtl.
bool obj_render(const ObjCorners& c, Animation* anim, std::string* error);

// The material library obj_render recorded in a file's materials JSON (MATL), or "".
std::string obj_material_library(const std::string& materials_json);

}  // namespace dcurve
