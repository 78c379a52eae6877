#include "cli/face_order_text.h"

namespace dcurve::cli {

std::string face_order_text(uint64_t triangles, bool coder_order, uint64_t face_bytes, uint64_t coder_order_bytes) {
  const std::string count = std::to_string(triangles) + " triangles";
  if (coder_order)
    return count + " in the face coder's order (vertex ids and windings as given): " + std::to_string(face_bytes) +
           " bytes";
  return count + " in the order given (the exact index buffer): " + std::to_string(face_bytes) +
         " bytes; in the face coder's order " + std::to_string(coder_order_bytes);
}

const char* face_order_name(bool coder_order) { return coder_order ? "coder" : "exact"; }

}  // namespace dcurve::cli
