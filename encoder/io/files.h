// Whole-file reads and crash-safe writes.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

bool read_file(const std::string& path, std::vector<uint8_t>* bytes, std::string* error);

// The file name's extension with its dot, lower case (".obj" for "a/B.OBJ"; "" when none).
std::string lowercase_extension(const std::string& path);

// Writes to "<path>.tmp.<pid>" and renames over `path`, so readers never see a partial file
// and a failed write leaves nothing behind.
bool write_file_atomic(const std::string& path, const void* data, size_t size, std::string* error);

}  // namespace dcurve
