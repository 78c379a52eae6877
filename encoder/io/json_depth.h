// A JSON text's nesting depth, measured without parsing it: recursive parsers (tinygltf
// converts extras and extensions recursively) overflow the stack on a few KB of brackets.
#pragma once
#include <cstddef>
#include <string>

namespace dcurve {

// Deeper than any glTF needs (its own structure is 6 levels; extras rarely add many).
constexpr int kMaxJsonDepth = 128;

// False, with an error, when arrays and objects nest deeper than `max_depth` (brackets inside
// strings do not count).
bool check_json_depth(const char* text, size_t size, int max_depth, std::string* error);

}  // namespace dcurve
