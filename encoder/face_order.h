// The order the FACE section stores triangles in: the face coder's order (the default: the
// same triangles, windings and vertex ids, coded far smaller) or the input's index buffer as
// given (--keep-face-order). Also what `dcurve encode -v` and `dcurve info` say about it.
#pragma once
#include <cstdint>
#include <vector>

namespace dcurve {

// The face coder's traversal order of `faces` or `faces` as given, whichever gives the smaller
// FACE section: traversal wins on irregular meshes, a regular grid's own order can beat it.
std::vector<uint32_t> smaller_face_order(const std::vector<uint32_t>& faces);

struct FaceOrderUse {
  bool coder_order = false;           // the list is the face coder's traversal order
  uint64_t coder_order_bytes = 0;     // FACE section (header included) of that order of the same triangles
};

// How `faces` (as a file stores them) relate to the coder's order. Costs one traversal and one
// FACE coding of the list: cheap beside an encode, a few tens of ms for 20k triangles.
FaceOrderUse face_order_use(const std::vector<uint32_t>& faces);

}  // namespace dcurve
