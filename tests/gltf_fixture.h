// A small glTF written by hand for the reader's tests: the JSON as nlohmann::json, so each
// test edits one field, and its buffer file.
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <fstream>
#include <string>

namespace dcurve::test {

// A two-frame glTF: one triangle, one morph target lifting it by 1 in z, keys at 0 and
// 0.5 s with weights 0 and 1. buf.bin: positions (36 B), target (36 B), indices (12 B),
// times (8 B), weights (8 B).
inline nlohmann::json triangle_gltf() {
  return nlohmann::json::parse(R"({
    "asset": {"version": "2.0"},
    "buffers": [{"uri": "buf.bin", "byteLength": 100}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 12},
                    {"buffer": 0, "byteOffset": 84, "byteLength": 8},
                    {"buffer": 0, "byteOffset": 92, "byteLength": 8}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,0], "max": [1,1,0]},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0,0,1], "max": [0,0,1]},
                  {"bufferView": 2, "componentType": 5125, "count": 3, "type": "SCALAR"},
                  {"bufferView": 3, "componentType": 5126, "count": 2, "type": "SCALAR", "min": [0], "max": [0.5]},
                  {"bufferView": 4, "componentType": 5126, "count": 2, "type": "SCALAR"}],
    "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 2,
                                               "targets": [{"POSITION": 1}]}]}],
    "nodes": [{"mesh": 0}],
    "scenes": [{"nodes": [0]}],
    "animations": [{"samplers": [{"input": 3, "output": 4}],
                    "channels": [{"sampler": 0, "target": {"node": 0, "path": "weights"}}]}]
  })");
}

inline void write_triangle_buffer(const std::string& path) {
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, target[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  const uint32_t idx[3] = {0, 1, 2};
  const float times[2] = {0, 0.5f}, weights[2] = {0, 1};
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(pos), 36).write(reinterpret_cast<const char*>(target), 36);
  out.write(reinterpret_cast<const char*>(idx), 12).write(reinterpret_cast<const char*>(times), 8);
  out.write(reinterpret_cast<const char*>(weights), 8);
}

}  // namespace dcurve::test
