// Whole-file reads, extensions, and which files are the same (writes: encoder/io/output_file.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

bool read_file(const std::string& path, std::vector<uint8_t>* bytes, std::string* error);

// The file name's extension with its dot, lower case (".obj" for "a/B.OBJ"; "" when none).
std::string lowercase_extension(const std::string& path);

// Whether `path` exists and is the same file as one of `inputs` (links followed); refusing
// it keeps a command from overwriting what it reads.
bool is_one_of(const std::string& path, const std::vector<std::string>& inputs);

}  // namespace dcurve
