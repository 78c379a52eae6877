// The resource policy of glTF input: which files a glTF's buffer uris may name, checked and
// sized from the JSON before tinygltf (or anything else) opens a file.
// - A uri is a path relative to the glTF's own folder; after following links it must lie in
//   that folder or in one of ReadLimits::resource_dirs. Absolute paths, other schemes
//   (file:, http:) and malformed %-escapes are refused; no other folder is searched.
// - A buffer file must be a regular file of exactly its byteLength; folders, FIFOs and
//   devices are refused by name without being opened for reading.
// - Only buffers an accessor uses are read; images are never read (dcurve uses none).
// - data: uris are at most kMaxDataUriBytes and no longer than their byteLength needs.
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "encoder/io/read_limits.h"

namespace dcurve {

constexpr uint64_t kMaxDataUriBytes = uint64_t(256) << 20;

// One external buffer file as planned: where it is, its size, and whether an accessor uses it.
struct PlannedBuffer {
  std::string path;  // resolved; empty for a buffer nothing uses (its bytes are zeros, never read)
  uint64_t byte_length = 0;
  int serves_left = 0;  // buffers naming this uri that tinygltf may still ask for
};

// The external buffers of one glTF, keyed by the uri as tinygltf decodes it.
struct BufferPlan {
  std::map<std::string, PlannedBuffer> files;
};

// What '+' means in a uri: itself (RFC 3986, how dcurve finds a file), or a space (how
// tinygltf decodes a buffer's uri before it asks for the file: the key it is served by).
enum class UriPlus { Literal, Space };

// Percent-decodes a uri; false on a '%' that is not followed by two hex digits.
bool decode_uri(const std::string& uri, std::string* decoded, UriPlus plus = UriPlus::Literal);

// The file `uri` names, under the policy above: `gltf_dir` is the glTF's folder.
bool resolve_resource(const std::string& gltf_dir, const std::vector<std::string>& allowed_dirs,
                      const std::string& uri, std::string* path, std::string* error);

// Reads the glTF JSON `json` (depth already checked), takes every buffer's byteLength from
// `budget`, checks data: uris and resolves and checks every used external buffer file.
bool plan_gltf_buffers(const std::string& json, const std::string& gltf_dir, const ReadLimits& limits,
                       MemoryBudget* budget, BufferPlan* plan, std::string* error);

// Reads a planned buffer file: opened non-blocking, refused unless it is still a regular file
// of exactly its byteLength.
bool read_planned_buffer(const PlannedBuffer& buffer, std::vector<unsigned char>* bytes, std::string* error);

}  // namespace dcurve
