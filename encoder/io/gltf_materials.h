// The materials a glTF mesh's primitives use, carried into the file (MATL): the materials,
// the textures, samplers and images they reference, re-indexed, and the images' bytes.
// Images are read only when a used material needs them, under the resource policy of
// gltf_resources.h (a file beside the glTF, a bufferView, or a data: uri).
#pragma once
#include <nlohmann/json.hpp>

#include <set>
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"
#include "encoder/io/read_limits.h"

namespace tinygltf {
class Model;
}

namespace dcurve {

// The images the materials of any mesh primitive reference through their textures: the only
// images a reader opens.
std::set<int64_t> used_images(const nlohmann::json& doc);

// `materials` (input indices, -1 none), the materials of the groups in order, become
// out->json (the used materials, textures, samplers and images, renumbered in order of first
// use) and out->images; *renumbered receives each group's index in out->json's "materials".
// `doc` is the file's JSON, `model` tinygltf's reading of it (the image bytes of bufferViews
// and data: uris), `gltf_dir` its folder.
bool read_gltf_materials(const nlohmann::json& doc, const tinygltf::Model& model, const std::vector<int>& materials,
                         const std::string& gltf_dir, const ReadLimits& limits, MemoryBudget* budget, MaterialSet* out,
                         std::vector<int>* renumbered, std::string* error);

}  // namespace dcurve
