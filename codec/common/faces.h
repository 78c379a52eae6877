// The FACE section payload (format_spec/dcrv.md, section FACE, describes every byte). Vertex
// ids are never renumbered. Three layouts: Exact reproduces the triangle list as given;
// Traversal may reorder triangles and rotate their corners (winding kept), which lets each
// triangle be coded from the edge it shares with an earlier one (zstd, applied by the
// container, does the entropy coding of both); Compact reproduces any list exactly too, but
// is built around the traversal and range-codes it (codec/common/faces_compact.h), so it is
// by far the smallest for a list already in traversal_order. codec/compress/faces_encoder.h
// writes the layouts, codec/decompress/faces_decoder.h reads them.
#pragma once
#include <cstdint>

namespace dcurve {

enum class FaceOrder : uint8_t {
  Exact = 0,      // same triangles, same order, same first corner
  Traversal = 1,  // same triangles and windings, in a breadth-first order over shared edges
  Compact = 2,    // same list exactly; small when the list is in traversal_order
};

}  // namespace dcurve
