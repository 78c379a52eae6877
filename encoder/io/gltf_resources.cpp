#include "encoder/io/gltf_resources.h"

#include <sys/stat.h>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/gltf_materials.h"
#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = char(std::tolower(static_cast<unsigned char>(c)));
  return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

// "scheme:" at the start (RFC 3986: a letter, then letters, digits, + - .).
bool has_scheme(const std::string& uri) {
  size_t i = 0;
  if (uri.empty() || !std::isalpha(static_cast<unsigned char>(uri[0]))) return false;
  while (i < uri.size() && (std::isalnum(static_cast<unsigned char>(uri[i])) || uri[i] == '+' || uri[i] == '-' || uri[i] == '.'))
    ++i;
  return i < uri.size() && uri[i] == ':';
}

bool is_inside(const fs::path& path, const fs::path& dir) {
  auto p = path.begin();
  for (auto d = dir.begin(); d != dir.end(); ++d, ++p)
    if (p == path.end() || *p != *d) return false;
  return true;
}

// Whether `path` lies in the glTF's folder `base` or one of `allowed_dirs`.
bool allowed_place(const fs::path& path, const fs::path& base, const std::vector<std::string>& allowed_dirs) {
  if (is_inside(path, base)) return true;
  for (const std::string& dir : allowed_dirs) {
    std::error_code ec;
    const fs::path d = fs::canonical(dir, ec);
    if (!ec && is_inside(path, d)) return true;
  }
  return false;
}

// The accessors' buffers: those of the bufferViews an accessor (or its sparse part) or a used
// image names.
std::set<int64_t> used_buffers(const json& doc) {
  std::set<int64_t> views, buffers;
  auto add_view = [&views](const json& owner) {
    auto it = owner.find("bufferView");
    if (it != owner.end() && it->is_number_integer()) views.insert(it->get<int64_t>());
  };
  const json& accessors = doc.contains("accessors") ? doc["accessors"] : json::array();
  for (const json& a : accessors.is_array() ? accessors : json::array()) {
    if (!a.is_object()) continue;
    add_view(a);
    auto sparse = a.find("sparse");
    if (sparse == a.end() || !sparse->is_object()) continue;
    for (const char* part : {"indices", "values"})
      if (sparse->contains(part) && (*sparse)[part].is_object()) add_view((*sparse)[part]);
  }
  // The images a used material needs (gltf_materials.h): their bufferViews' buffers are read too.
  const json& images = doc.contains("images") && doc["images"].is_array() ? doc["images"] : json::array();
  for (int64_t i : used_images(doc))
    if (i >= 0 && size_t(i) < images.size() && images[size_t(i)].is_object()) add_view(images[size_t(i)]);
  const json& bv = doc.contains("bufferViews") ? doc["bufferViews"] : json::array();
  for (int64_t v : views)
    if (bv.is_array() && v >= 0 && size_t(v) < bv.size() && bv[size_t(v)].is_object() && bv[size_t(v)].contains("buffer") &&
        bv[size_t(v)]["buffer"].is_number_integer())
      buffers.insert(bv[size_t(v)]["buffer"].get<int64_t>());
  return buffers;
}

// A data: uri longer than its bytes need (base64 plus its header) carries nothing dcurve reads.
bool check_data_uri(const std::string& what, const std::string& uri, uint64_t byte_length, std::string* error) {
  const uint64_t needed = 4 * ((byte_length + 2) / 3) + 128;  // 128: room for a media type
  if (uri.size() > kMaxDataUriBytes || uri.size() > needed)
    return fail(error, what + ": its data: uri is " + std::to_string(uri.size()) + " bytes, more than " +
                           (uri.size() > kMaxDataUriBytes ? "the limit of " + std::to_string(kMaxDataUriBytes)
                                                          : "its byteLength of " + std::to_string(byte_length) + " needs"));
  return true;
}

// Resolves a used buffer's file and checks its type and size against byteLength.
bool plan_external_buffer(const std::string& what, const std::string& uri, uint64_t byte_length, bool used,
                          const std::string& gltf_dir, const ReadLimits& limits, BufferPlan* plan, std::string* error) {
  std::string key, path, err;
  if (!decode_uri(uri, &key, UriPlus::Space)) return fail(error, what + ": uri '" + quote_file_text(uri) + "' has a malformed %-escape");
  PlannedBuffer& entry = plan->files[key];
  ++entry.serves_left;
  entry.byte_length = byte_length;
  if (!used) return true;
  if (!resolve_resource(gltf_dir, limits.resource_dirs, uri, &path, &err)) return fail(error, what + ": " + err);
  // tinygltf asks for "a b.bin" both for "a+b.bin" and for "a%20b.bin": two files it cannot tell apart.
  if (!entry.path.empty() && entry.path != path)
    return fail(error, what + ": uri '" + quote_file_text(uri) + "' and another buffer's name two files that tinygltf reads as one");
  if (!entry.path.empty()) return true;
  entry.path = path;
  struct stat st;
  if (stat(entry.path.c_str(), &st) != 0)
    return fail(error, what + ": uri '" + quote_file_text(uri) + "': " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    return fail(error, what + ": uri '" + quote_file_text(uri) + "' is " + file_type_name(st.st_mode) + ", not a regular file");
  if (uint64_t(st.st_size) != byte_length)
    return fail(error, what + ": uri '" + quote_file_text(uri) + "' is " + std::to_string(st.st_size) +
                           " bytes, but its byteLength is " + std::to_string(byte_length));
  return true;
}

bool plan_buffer(const json& b, size_t index, bool used, const std::string& gltf_dir, const ReadLimits& limits,
                 MemoryBudget* budget, BufferPlan* plan, std::string* error) {
  const std::string what = "buffer " + std::to_string(index);
  if (!b.is_object() || !b.contains("byteLength") || !b["byteLength"].is_number_unsigned())
    return fail(error, what + ": no byteLength");
  const uint64_t byte_length = b["byteLength"].get<uint64_t>();
  if (!budget->take(byte_length, 1, what, error)) return false;
  if (!b.contains("uri")) return true;  // a .glb's BIN chunk
  if (!b["uri"].is_string()) return fail(error, what + ": its uri is not a string");
  const std::string& uri = b["uri"].get_ref<const std::string&>();
  if (uri.rfind("data:", 0) == 0) return check_data_uri(what, uri, byte_length, error);
  return plan_external_buffer(what, uri, byte_length, used, gltf_dir, limits, plan, error);
}

// Images are never read, but tinygltf decodes their data: uris.
bool check_image_data_uris(const json& doc, std::string* error) {
  if (!doc.contains("images") || !doc["images"].is_array()) return true;
  for (size_t i = 0; i < doc["images"].size(); ++i) {
    const json& im = doc["images"][i];
    if (im.is_object() && im.contains("uri") && im["uri"].is_string() && im["uri"].get_ref<const std::string&>().size() > kMaxDataUriBytes)
      return fail(error, "image " + std::to_string(i) + ": its uri is longer than " + std::to_string(kMaxDataUriBytes) + " bytes");
  }
  return true;
}

}  // namespace

bool decode_uri(const std::string& uri, std::string* decoded, UriPlus plus) {
  decoded->clear();
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '+' && plus == UriPlus::Space) {
      decoded->push_back(' ');
    } else if (uri[i] == '%') {
      if (i + 2 >= uri.size()) return false;
      const int hi = hex_value(uri[i + 1]), lo = hex_value(uri[i + 2]);
      if (hi < 0 || lo < 0) return false;
      decoded->push_back(char(hi * 16 + lo));
      i += 2;
    } else {
      decoded->push_back(uri[i]);
    }
  }
  return true;
}

bool resolve_resource(const std::string& gltf_dir, const std::vector<std::string>& allowed_dirs,
                      const std::string& uri, std::string* path, std::string* error) {
  const std::string quoted = "uri '" + quote_file_text(uri) + "'";
  std::string name;
  if (has_scheme(uri)) return fail(error, quoted + " has a scheme dcurve does not read (only relative paths and data:)");
  if (!decode_uri(uri, &name)) return fail(error, quoted + " has a malformed %-escape");
  if (name.empty() || name.find('\0') != std::string::npos) return fail(error, quoted + " names no file");
  if (name[0] == '/' || name[0] == '\\') return fail(error, quoted + " is an absolute path; glTF resources are relative to the glTF's folder");
  std::error_code ec;
  const fs::path base = fs::canonical(gltf_dir.empty() ? "." : gltf_dir, ec);
  if (ec) return fail(error, "the glTF's folder: " + ec.message());
  // Checked as written (no folder of the path needs to exist) and again with links followed.
  const fs::path lexical = (base / name).lexically_normal();
  const fs::path real = fs::canonical(lexical, ec);
  if (!allowed_place(lexical, base, allowed_dirs) || (!ec && !allowed_place(real, base, allowed_dirs)))
    return fail(error, quoted + " leads outside the glTF's folder (" + quote_file_text((ec ? lexical : real).string()) +
                           "); dcurve reads resources only from that folder (widen with --allow-resources-outside DIR)");
  if (ec) return fail(error, quoted + ": " + (ec == std::errc::no_such_file_or_directory ? "no such file in the glTF's folder" : ec.message()));
  *path = real.string();
  return true;
}

bool plan_gltf_buffers(const std::string& text, const std::string& gltf_dir, const ReadLimits& limits,
                       MemoryBudget* budget, BufferPlan* plan, std::string* error) {
  const json doc = json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return fail(error, "cannot read glTF: its JSON is malformed");
  if (!check_image_data_uris(doc, error)) return false;
  if (!doc.contains("buffers")) return true;
  const json& buffers = doc["buffers"];
  if (!buffers.is_array()) return fail(error, "buffers is not an array");
  const std::set<int64_t> used = used_buffers(doc);
  for (size_t i = 0; i < buffers.size(); ++i)
    if (!plan_buffer(buffers[i], i, used.count(int64_t(i)) > 0, gltf_dir, limits, budget, plan, error)) return false;
  return true;
}

bool read_planned_buffer(const PlannedBuffer& buffer, std::vector<unsigned char>* bytes, std::string* error) {
  if (buffer.path.empty()) {  // no accessor reads it: zeros stand for its bytes
    bytes->assign(buffer.byte_length, 0);
    return true;
  }
  if (!read_file(buffer.path, bytes, error, buffer.byte_length)) return false;
  if (bytes->size() != buffer.byte_length)
    return fail(error, buffer.path + ": " + std::to_string(bytes->size()) + " bytes, but its byteLength is " +
                           std::to_string(buffer.byte_length));
  return true;
}

}  // namespace dcurve
