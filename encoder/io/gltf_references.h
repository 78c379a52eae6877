// The files a glTF names besides itself (buffers and images with a `uri` that is not a
// `data:` URI), as paths beside it: what an encode of it may read, so never an output.
// Read without building the document (a SAX pass over the JSON; a .glb's JSON chunk only).
#pragma once
#include <string>
#include <vector>

namespace dcurve {

// Empty when `path` is not a readable .gltf/.glb (its reader reports that).
std::vector<std::string> gltf_referenced_files(const std::string& path);

}  // namespace dcurve
