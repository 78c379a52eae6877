// Reading and writing the .dcrv container (format_spec/dcrv.md describes every byte).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

struct WriteOptions {
  bool connectivity = true;  // store faces; engines that already hold the mesh can drop them
  int zstd_level = 19;       // 1..22
};

// One section as found in a file, for `dcurve info`.
struct SectionInfo {
  std::string tag;        // four ASCII characters
  bool required = false;
  bool compressed = false;
  uint64_t stored_bytes = 0;  // bytes in the file (after the section header)
  uint64_t raw_bytes = 0;     // bytes after decompression
};

std::vector<uint8_t> write_container(const Model& model, const WriteOptions& options = {});

// Parses and validates a whole file. On failure returns false and a message naming the
// problem; never reads outside [data, data + size) and bounds every allocation by `size`.
bool read_container(const uint8_t* data, size_t size, Model* model, std::string* error,
                    std::vector<SectionInfo>* sections = nullptr);

}  // namespace dcurve
