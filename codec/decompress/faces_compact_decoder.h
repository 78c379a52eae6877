// Reading FACE layout 2, Compact (codec/common/faces_compact.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Decodes the bytes after the layout byte. False with a message when they are malformed;
// never reads outside [data, data + size), and its memory grows with the triangles
// actually decoded, which the bound of codec/common/faces_compact.h ties to `size`.
bool decode_compact_faces(const uint8_t* data, size_t size, std::vector<uint32_t>* faces, std::string* error);

}  // namespace dcurve
