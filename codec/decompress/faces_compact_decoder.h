// Reading FACE layout 2, Compact (codec/common/faces_compact.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Decodes the bytes after the layout byte of a file with `vertex_count` vertices (every id
// must be below it). False with a message when they are malformed; never reads outside
// [data, data + size). Its memory is about 5 bytes per vertex, then grows with the triangles
// actually decoded, which the bound of codec/common/faces_compact.h ties to `size`.
bool decode_compact_faces(const uint8_t* data, size_t size, uint32_t vertex_count, std::vector<uint32_t>* faces,
                          std::string* error);

}  // namespace dcurve
