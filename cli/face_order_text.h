// One sentence on a file's face layout for `dcurve encode -v` and `dcurve info`: whether the
// triangles are in the face coder's order or the input's exact index buffer, and for the
// exact one, what the coder's order would have taken.
#pragma once
#include <cstdint>
#include <string>

namespace dcurve::cli {

// "16843 triangles in the face coder's order (vertex ids and windings as given): 13049 bytes"
// or "... in the order given (the exact index buffer): 66675 bytes; in the face coder's order
// 13049". Bytes are the FACE section's, header included.
std::string face_order_text(uint64_t triangles, bool coder_order, uint64_t face_bytes, uint64_t coder_order_bytes);

// "coder" or "exact": the JSON value of the same fact.
const char* face_order_name(bool coder_order);

}  // namespace dcurve::cli
