// FACE layout 2, Compact (format_spec/dcrv.md section 6.3): the triangle list coded as a
// breadth-first traversal with the adaptive binary range coder. Like the Exact layout it
// reproduces ANY list exactly (order, rotation, winding); it is small when the list is in
// traversal_order (codec/faces.h), because then almost every triangle follows from an edge
// of an earlier one and its third corner is either a vertex next to that edge on the
// decoded region's border (an index into a short candidate list) or a new vertex whose id
// is coded against ids the decoder already knows. Vertex ids are never renumbered.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Triangles the decoder accepts per payload byte (plus a fixed allowance): bounds the work
// and memory a small hostile payload can ask for. Real meshes need well under 16 per byte.
constexpr uint64_t kCompactFreeTriangles = 4096;
constexpr uint64_t kCompactTrianglesPerByte = 64;

// Appends the layout-2 payload for `faces` (3 ids per triangle, each < 2^32 - 1) after the
// layout byte, which the caller writes. False (nothing usable appended) when the list is
// too compressible for the decoder's triangle bound; the caller then uses another layout.
bool encode_compact_faces(const std::vector<uint32_t>& faces, std::vector<uint8_t>* out);

// Decodes the bytes after the layout byte. False with a message when they are malformed;
// never reads outside [data, data + size), and its memory grows with the triangles
// actually decoded, which the bound above ties to `size`.
bool decode_compact_faces(const uint8_t* data, size_t size, std::vector<uint32_t>* faces, std::string* error);

}  // namespace dcurve
