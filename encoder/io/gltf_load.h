// Loading a glTF file into tinygltf's model under the resource policy (gltf_resources.h):
// tinygltf parses, but every file it reads is served by dcurve's callbacks.
#pragma once
#include <string>

#include "encoder/io/read_limits.h"

namespace tinygltf {
class Model;
}

namespace dcurve {

// Reads `path` (.gltf or .glb) and the buffers its accessors use. Refused before tinygltf
// parses it: a special file, JSON nested deeper than kMaxJsonDepth, buffers over `budget`,
// a resource the policy refuses. Errors do not name the file (the caller does). `json`, when
// given, receives the file's JSON text. Images keep their bytes undecoded (data: uris' and
// bufferViews' as tinygltf found them; files are never opened here).
bool load_gltf_model(const std::string& path, const ReadLimits& limits, MemoryBudget* budget, tinygltf::Model* model,
                     std::string* error, std::string* json = nullptr);

}  // namespace dcurve
