// Reading the FACE section payload (codec/common/faces.h describes the layouts), as
// codec/compress/faces_encoder.h wrote it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/faces.h"

namespace dcurve {

// Reverses encode_faces. Returns false with a message when the bytes are malformed; never
// reads outside [data, data + size); memory is bounded by a constant times size (Exact and
// Traversal: 12 bytes per input byte; Compact: its triangle-per-byte bound).
bool decode_faces(const uint8_t* data, size_t size, std::vector<uint32_t>* faces, std::string* error);

}  // namespace dcurve
