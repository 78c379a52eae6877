#include "encoder/io/gltf_load.h"

#include <tiny_gltf.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/gltf_resources.h"
#include "encoder/io/json_depth.h"
#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace {

// tinygltf joins this to every uri it looks up; what does not start with it came from its
// search of the current folder, which the policy does not allow.
const std::string kBaseToken = "dcurve-gltf-folder";

// What the file-system callbacks serve: the planned buffers, and the first refusal.
struct Server {
  BufferPlan plan;
  std::string error;
};

PlannedBuffer* planned(const std::string& path, Server* server) {
  if (path.compare(0, kBaseToken.size() + 1, kBaseToken + "/") != 0) return nullptr;
  auto it = server->plan.files.find(path.substr(kBaseToken.size() + 1));
  return it == server->plan.files.end() || it->second.serves_left <= 0 ? nullptr : &it->second;
}

bool file_exists(const std::string& path, void* user) { return planned(path, static_cast<Server*>(user)) != nullptr; }

std::string expand_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  Server* server = static_cast<Server*>(user);
  PlannedBuffer* buffer = planned(path, server);
  if (!buffer) return false;
  --buffer->serves_left;  // an image naming the same file is not served
  if (read_planned_buffer(*buffer, out, &server->error)) return true;
  if (err) *err = "refused";
  return false;
}

bool write_whole_file(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images are never decoded: the bytes tinygltf found (a data: uri's or a bufferView's) are
// kept as they are for the materials a mesh carries (gltf_materials.h). A file an image
// names is not served (not planned), so none is opened here.
bool keep_image_bytes(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// The JSON text of a .gltf, or of a .glb's first chunk (GLB: 12-byte header, then chunks of
// length, type, data).
bool json_text(const std::vector<uint8_t>& bytes, bool binary, std::string* text, std::string* error) {
  if (!binary) {
    text->assign(bytes.begin(), bytes.end());
    return true;
  }
  uint32_t length = 0, type = 0;
  if (bytes.size() >= 20) {
    std::memcpy(&length, &bytes[12], 4);
    std::memcpy(&type, &bytes[16], 4);
  }
  if (bytes.size() < 20 || std::memcmp(bytes.data(), "glTF", 4) != 0 || type != 0x4E4F534A || length > bytes.size() - 20)
    return fail(error, "cannot read glTF: not a glTF binary file (no glTF header and JSON chunk)");
  text->assign(bytes.begin() + 20, bytes.begin() + 20 + length);
  return true;
}

bool parse_model(const std::vector<uint8_t>& bytes, bool binary, Server* server, tinygltf::Model* model,
                 std::string* error) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keep_image_bytes, nullptr);
  loader.SetFsCallbacks({file_exists, expand_path, read_whole_file, write_whole_file, server});
  std::string err, warn;
  const bool ok =
      binary ? loader.LoadBinaryFromMemory(model, &err, &warn, bytes.data(), unsigned(bytes.size()), kBaseToken)
             : loader.LoadASCIIFromString(model, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                          unsigned(bytes.size()), kBaseToken);
  if (ok) return true;
  if (!server->error.empty()) return fail(error, server->error);
  while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();  // tinygltf ends lines with \n
  return fail(error, "cannot read glTF: " + (err.empty() ? std::string("malformed file") : quote_file_text(err)));
}

}  // namespace

bool load_gltf_model(const std::string& path, const ReadLimits& limits, MemoryBudget* budget, tinygltf::Model* model,
                     std::string* error, std::string* json) {
  std::vector<uint8_t> bytes;
  std::string text, err;
  const bool binary = lowercase_extension(path) == ".glb";
  if (!read_file(path, &bytes, &err, limits.max_memory)) {
    const std::string prefix = path + ": ";
    return fail(error, err.compare(0, prefix.size(), prefix) == 0 ? err.substr(prefix.size()) : err);
  }
  if (bytes.size() > UINT32_MAX) return fail(error, "larger than 4 GiB, which tinygltf cannot read");
  Server server;
  const std::string dir = std::filesystem::path(path).parent_path().string();
  return budget->take(bytes.size(), 1, "the file", error) && json_text(bytes, binary, &text, error) &&
         check_json_depth(text.data(), text.size(), kMaxJsonDepth, error) &&
         plan_gltf_buffers(text, dir, limits, budget, &server.plan, error) &&
         parse_model(bytes, binary, &server, model, error) && (!json || (*json = std::move(text), true));
}

}  // namespace dcurve
