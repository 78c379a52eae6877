// What an OBJ's faces say besides positions: each corner's texture coordinate and normal
// (`f v/vt/vn`), each face's material (`usemtl`) and the material library (`mtllib`), as
// obj_reader.h parses them, turned into render vertices and material groups
// (Animation::render).
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

// anim->render (render vertices sorted by vertex, copies in order of first use; UVs flipped
// to glTF's v), groups and material names from `c`, whose triangles must be anim->faces.
// Nothing when the file has neither vt, vn nor usemtl.
bool obj_render(const ObjCorners& c, Animation* anim, std::string* error);

// The material library obj_render recorded in a file's materials JSON (MATL), or "".
std::string obj_material_library(const std::string& materials_json);

}  // namespace dcurve
