// The FACE section payload (format_spec/dcrv.md, section FACE, describes every byte). Vertex
// ids are never renumbered. Three layouts: Exact reproduces the triangle list as given;
// Traversal may reorder triangles and rotate their corners (winding kept), which lets each
// triangle be coded from the edge it shares with an earlier one (zstd, applied by the
// container, does the entropy coding of both); Compact reproduces any list exactly too, but
// is built around the traversal and range-codes it (codec/faces_compact.h), so it is by far
// the smallest for a list already in traversal_order.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

enum class FaceOrder : uint8_t {
  Exact = 0,      // same triangles, same order, same first corner
  Traversal = 1,  // same triangles and windings, in a breadth-first order over shared edges
  Compact = 2,    // same list exactly; small when the list is in traversal_order
};

// Codes `faces` (3 vertex ids per triangle, any values < 2^32 - 1) into bytes. Compact falls
// back to Exact for a list too compressible for the decoder's triangle-per-byte bound.
std::vector<uint8_t> encode_faces(const std::vector<uint32_t>& faces, FaceOrder order = FaceOrder::Exact);

// The triangle list a reader gets back from the Traversal layout: the same triangles and
// windings, reordered and rotated; also the order the Compact layout codes smallest. An encoder that wants the compact layout puts its faces in
// this order BEFORE anything else depends on face order (the residual coder's neighbours),
// since write_container only uses Traversal when it gives back model.faces unchanged.
std::vector<uint32_t> traversal_order(const std::vector<uint32_t>& faces);

// Reverses encode_faces. Returns false with a message when the bytes are malformed; never
// reads outside [data, data + size); memory is bounded by a constant times size (Exact and
// Traversal: 12 bytes per input byte; Compact: its triangle-per-byte bound).
bool decode_faces(const uint8_t* data, size_t size, std::vector<uint32_t>* faces, std::string* error);

}  // namespace dcurve
