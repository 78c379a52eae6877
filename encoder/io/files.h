// Whole-file reads, extensions, and which files are the same (writes: encoder/io/output_file.h).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Reads the whole of a regular file (links followed) of at most `max_bytes` bytes. A folder,
// FIFO, device or socket is refused without waiting on it (opened non-blocking), and the size
// is checked before anything is allocated; errors name the file.
bool read_file(const std::string& path, std::vector<uint8_t>* bytes, std::string* error,
               uint64_t max_bytes = UINT64_MAX);

// Whether `path` is a regular file (links followed); otherwise false and an error naming what
// it is ("is a FIFO", "does not exist", ...).
bool check_input_file(const std::string& path, std::string* error);

// What a file of mode `st_mode` is, for messages: "a symbolic link", "a FIFO", "a folder", ...
const char* file_type_name(unsigned st_mode);

// The folder that holds `path` ("." for a bare file name): where an output's temporary goes.
std::string containing_folder(const std::string& path);

// The file name's extension with its dot, lower case (".obj" for "a/B.OBJ"; "" when none).
std::string lowercase_extension(const std::string& path);

// Whether `path` exists and is the same file as one of `inputs` (links followed); refusing
// it keeps a command from overwriting what it reads.
bool is_one_of(const std::string& path, const std::vector<std::string>& inputs);

}  // namespace dcurve
