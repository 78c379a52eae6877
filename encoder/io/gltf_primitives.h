// A glTF mesh's triangle primitives (one per material, as exporters write them) read and
// joined into one geometry: positions, morph targets, static attributes, and which primitive
// each triangle came from.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/animation.h"
#include "encoder/io/read_limits.h"

namespace tinygltf {
class Model;
class Mesh;
}

namespace dcurve {

struct GltfGeometry {
  std::vector<float> base;                     // POSITION, primitive after primitive
  std::vector<uint32_t> faces;                 // indices, offset to the joined vertices
  std::vector<std::vector<float>> targets;     // per morph target; empty: moves no vertex
  std::vector<AnimationRender::Attribute> attributes;  // TEXCOORD_0/1, COLOR_0, NORMAL
  std::vector<int> materials;                  // per primitive, -1 for none
  std::vector<uint32_t> face_primitive;        // per triangle
};

// Reads every primitive of `mesh`. Refused: a primitive that is not TRIANGLES or has no
// POSITION, primitives with different morph target counts (glTF requires them equal), data
// the accessors cannot give (gltf_accessor.h), non-finite attribute values. An attribute
// some primitives lack is zero there; colours are widened to RGBA when primitives differ.
bool read_gltf_geometry(const tinygltf::Model& model, const tinygltf::Mesh& mesh, MemoryBudget* budget,
                        GltfGeometry* g, std::string* error);

// Bytes the joined geometry and `keys` frames of it will take, from the accessors' counts.
long double gltf_declared_bytes(const tinygltf::Model& model, const tinygltf::Mesh& mesh, uint64_t keys,
                                uint64_t* vertices, uint64_t* targets);

}  // namespace dcurve
