// Writing the FACE section payload (codec/common/faces.h describes the layouts;
// codec/decompress/faces_decoder.h reads them).
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/faces.h"

namespace dcurve {

// Codes `faces` (3 vertex ids per triangle, any values < 2^32 - 1) into bytes. Compact falls
// back to Exact for a list too compressible for the decoder's triangle-per-byte bound.
// traversal: with FaceOrder::Traversal, the list a reader decodes from the bytes.
std::vector<uint8_t> encode_faces(const std::vector<uint32_t>& faces, FaceOrder order = FaceOrder::Exact,
                                  std::vector<uint32_t>* traversal = nullptr);

// The triangle list a reader gets back from the Traversal layout: the same triangles and
// windings, reordered and rotated; also the order the Compact layout codes smallest. An encoder that wants the compact layout puts its faces in
// this order BEFORE anything else depends on face order (the residual coder's neighbours),
// since write_container only uses Traversal when it gives back model.faces unchanged.
std::vector<uint32_t> traversal_order(const std::vector<uint32_t>& faces);

}  // namespace dcurve
