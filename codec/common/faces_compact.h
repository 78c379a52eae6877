// FACE layout 2, Compact (format_spec/dcrv.md section 6.3): the triangle list coded as a
// breadth-first traversal with the adaptive binary range coder. Like the Exact layout it
// reproduces ANY list exactly (order, rotation, winding); it is small when the list is in
// traversal_order (codec/compress/faces_encoder.h), because then almost every triangle
// follows from an edge of an earlier one and its third corner is either a vertex next to
// that edge on the decoded region's border (an index into a short candidate list) or a new
// vertex whose id is coded against ids the decoder already knows. Vertex ids are never
// renumbered. codec/compress/faces_compact_encoder.h writes the layout,
// codec/decompress/faces_compact_decoder.h reads it; codec/common/faces_compact_walk.h is
// the traversal both run.
#pragma once
#include <cstdint>

namespace dcurve {

// Triangles the decoder accepts per payload byte (plus a fixed allowance): bounds the work
// and memory a small hostile payload can ask for. Real meshes need well under 16 per byte.
constexpr uint64_t kCompactFreeTriangles = 4096;
constexpr uint64_t kCompactTrianglesPerByte = 64;

// Both sides keep state per vertex id (about 5 bytes each), so the writer declines the layout
// (the caller falls back to Exact) when ids are far sparser than any mesh's: the largest id
// must be below kCompactFreeIds + kCompactIdsPerTriangle * T. A closed mesh has about T / 2.
constexpr uint64_t kCompactFreeIds = uint64_t(1) << 16;
constexpr uint64_t kCompactIdsPerTriangle = 12;

}  // namespace dcurve
