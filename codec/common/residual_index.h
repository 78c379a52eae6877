// The header and chunk index at the start of a residual payload (format_spec/residual.md):
// written by codec/compress (assemble_residual_payload), read by the decoder, and sized by
// the container writer, which stores it in RESI ahead of the chunk data.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "codec/common/residual.h"

namespace dcurve {

// Parses the header and chunk index at the start of a residual payload of a file with
// `frame_count` frames and (has_faces) a FACE section. Rejects an index whose chunk count
// disagrees with the frame count, whose chunks do not follow each other without gap or
// overlap, or that claims more data than `data_limit` bytes.
bool read_residual_index(const uint8_t* payload, size_t size, uint32_t frame_count, bool has_faces,
                         uint64_t data_limit, ResidualIndex* index, std::string* error);

}  // namespace dcurve
