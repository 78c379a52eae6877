// Reading the .dcrv container (format_spec/dcrv.md describes every byte), as
// codec/compress/container_writer.h wrote it.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/container_format.h"
#include "codec/common/model.h"

namespace dcurve {

// Values (floats or grid values) a decoder may build for a file of `file_bytes` bytes:
// max(2^23, 8192 * file_bytes), the bound that keeps a small hostile file from asking for
// gigabytes (format_spec/dcrv.md section 15). read_container rejects V * max(F, 1) * 3
// above it.
uint64_t decoder_value_budget(size_t file_bytes);

// Reads the header fields without checking anything else; false when size < 24 or the
// magic is wrong. For tools that describe a file that read_container already accepted.
bool peek_header(const uint8_t* data, size_t size, ContainerHeader* header);

// Parses and validates a whole file. On failure returns false and a message naming the
// problem; never reads outside [data, data + size) and bounds every allocation by `size`.
// model->residual.payload receives the chunk index and the chunks.
bool read_container(const uint8_t* data, size_t size, Model* model, std::string* error,
                    std::vector<SectionInfo>* sections = nullptr);

// The file header alone (kContainerHeaderBytes of `data`), checked: magic, CRC, version,
// flags, and head_bytes within [kContainerHeaderBytes, file_bytes]. What a reader that
// loads chunks on demand reads first, to learn how much more it needs before any chunk.
bool read_container_header(const uint8_t* data, size_t size, uint64_t file_bytes, ContainerHeader* header,
                           std::string* error);

// Parses and validates the head of a file of file_bytes bytes (head: its first
// header.head_bytes bytes, as read_container_header gave them): everything but the chunk
// data, which it checks only by size against the chunk index. model->residual.payload
// receives the index alone and residual.external_bytes the chunk data's size, which
// starts at file offset head_bytes.
bool read_container_head(const uint8_t* head, size_t head_size, uint64_t file_bytes, Model* model,
                         std::string* error, std::vector<SectionInfo>* sections = nullptr);

}  // namespace dcurve
