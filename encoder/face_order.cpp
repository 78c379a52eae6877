#include "encoder/face_order.h"

#include "codec/compress/container_writer.h"
#include "codec/compress/faces_encoder.h"

namespace dcurve {

// Comparing FACE sections, not whole files: the residual coder's neighbours also follow the
// face order, but coding the residual twice to find out would double the encoding time.
std::vector<uint32_t> smaller_face_order(const std::vector<uint32_t>& faces) {
  std::vector<uint32_t> trav = traversal_order(faces);
  return face_payload_bytes(trav) < face_payload_bytes(faces) ? trav : faces;
}

FaceOrderUse face_order_use(const std::vector<uint32_t>& faces) {
  FaceOrderUse use;
  if (faces.empty()) return use;
  const std::vector<uint32_t> trav = traversal_order(faces);
  use.coder_order = trav == faces;
  use.coder_order_bytes = face_section_bytes(trav);
  return use;
}

}  // namespace dcurve
