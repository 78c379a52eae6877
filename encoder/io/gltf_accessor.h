// Reading glTF accessors into flat arrays with every offset, stride and count checked
// against the buffers (tinygltf parses the JSON but leaves the bytes to the caller), and
// sparse accessors applied.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace dcurve {

class MemoryBudget;

// The float values of accessor `index` (count x components, `components` per element: 1
// SCALAR, 2 VEC2, 3 VEC3, 4 VEC4), FLOAT, or with `allow_normalized` also normalized
// UNSIGNED_BYTE / UNSIGNED_SHORT read as [0, 1], as glTF allows for texture coordinates and
// colours (positions quantized so need the node's transform: refused). Errors say which accessor and why; `what` names its role
// ("POSITION", "morph target 2", ...). The array is taken from `budget` before it is
// allocated. A bufferView's byteStride must hold an element and be a multiple of 4.
bool read_float_accessor(const tinygltf::Model& model, int index, int components, const std::string& what,
                         MemoryBudget* budget, std::vector<float>* out, std::string* error,
                         bool allow_normalized = false);

// The values of an index accessor (SCALAR, UNSIGNED_BYTE/SHORT/INT).
bool read_index_accessor(const tinygltf::Model& model, int index, MemoryBudget* budget, std::vector<uint32_t>* out,
                         std::string* error);

}  // namespace dcurve
