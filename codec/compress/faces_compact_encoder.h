// Writing FACE layout 2, Compact (codec/common/faces_compact.h).
#pragma once
#include <cstdint>
#include <vector>

namespace dcurve {

// Appends the layout-2 payload for `faces` (3 ids per triangle, each < 2^32 - 1) after the
// layout byte, which the caller writes. False (nothing usable appended) when the list is
// too compressible for the decoder's triangle bound; the caller then uses another layout.
bool encode_compact_faces(const std::vector<uint32_t>& faces, std::vector<uint8_t>* out);

}  // namespace dcurve
