// Where a decoder finds the bytes of a chunk: a copy of the file's chunk data held in
// memory, or the file itself, read when a chunk is needed. Internal to the decoder library.
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "dcurve.hpp"

namespace dcurve {

class ChunkSource {
 public:
  virtual ~ChunkSource() = default;
  // The `size` bytes at `offset` of the chunk data: a pointer into the source's own memory,
  // or into *buffer after a read. Null with a message when they cannot be read. Safe to
  // call from several threads at once (each with its own buffer).
  virtual const uint8_t* fetch(uint64_t offset, uint64_t size, std::vector<uint8_t>* buffer, Error* error) const = 0;
  virtual size_t memory_bytes() const = 0;
};

// A copy of `size` bytes of chunk data.
std::unique_ptr<ChunkSource> memory_chunks(const uint8_t* data, size_t size);

// The chunk data of an open file (owned, closed by the source) at file offset
// `data_offset`, `data_size` bytes long; `path` names the file in messages.
std::unique_ptr<ChunkSource> file_chunks(std::FILE* file, uint64_t data_offset, uint64_t data_size,
                                         const std::string& path);

}  // namespace dcurve
