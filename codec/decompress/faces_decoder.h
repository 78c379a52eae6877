// Reading the FACE section payload (codec/common/faces.h describes the layouts), as
// codec/compress/faces_encoder.h wrote it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/faces.h"

namespace dcurve {

// Reverses encode_faces for a file with `vertex_count` vertices. Returns false with a message
// when the bytes are malformed; never reads outside [data, data + size); memory is bounded by
// a constant times size (Exact and Traversal: 12 bytes per input byte; Compact: its
// triangle-per-byte bound, plus about 5 bytes per vertex). Only Compact checks the ids
// against vertex_count as it reads them (it keeps per-vertex state); every layout's ids are
// checked by validate_model.
bool decode_faces(const uint8_t* data, size_t size, uint32_t vertex_count, std::vector<uint32_t>* faces,
                  std::string* error);

}  // namespace dcurve
