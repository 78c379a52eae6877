#include "encoder/io/gltf_materials.h"

#include <tiny_gltf.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/gltf_resources.h"
#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace {

using Json = nlohmann::json;

const Json& array_of(const Json& doc, const char* key) {
  static const Json empty = Json::array();
  auto it = doc.find(key);
  return it != doc.end() && it->is_array() ? *it : empty;
}

// Old index -> new index in order of first use.
struct Renumbering {
  std::map<int64_t, int64_t> to_new;
  std::vector<int64_t> order;  // old indices by new index
  int64_t add(int64_t old) {
    auto [it, fresh] = to_new.emplace(old, int64_t(order.size()));
    if (fresh) order.push_back(old);
    return it->second;
  }
};

bool is_texture_key(const std::string& key) {
  return key.size() >= 7 && key.compare(key.size() - 7, 7, "Texture") == 0;
}

// Every textureInfo of a material (an object under a key ending in "Texture", core or
// extension, with an integer "index"), renumbered through `textures`.
void renumber_texture_refs(Json* node, Renumbering* textures) {
  if (node->is_array()) {
    for (Json& v : *node) renumber_texture_refs(&v, textures);
    return;
  }
  if (!node->is_object()) return;
  for (auto it = node->begin(); it != node->end(); ++it) {
    Json& v = it.value();
    if (is_texture_key(it.key()) && v.is_object() && v.contains("index") && v["index"].is_number_integer())
      v["index"] = textures->add(v["index"].get<int64_t>());
    else
      renumber_texture_refs(&v, textures);
  }
}

// A texture's image: "source", or an extension's "source" (KHR_texture_basisu, EXT_texture_webp).
template <class Visit>
void for_each_image_ref(Json* texture, Visit visit) {
  if (texture->contains("source") && (*texture)["source"].is_number_integer()) visit(&(*texture)["source"]);
  if (!texture->contains("extensions") || !(*texture)["extensions"].is_object()) return;
  for (auto& ext : (*texture)["extensions"].items())
    if (ext.value().is_object() && ext.value().contains("source") && ext.value()["source"].is_number_integer())
      visit(&ext.value()["source"]);
}

bool valid_index(int64_t i, const Json& array) { return i >= 0 && size_t(i) < array.size(); }

std::string sniff_mime(const std::vector<uint8_t>& b) {
  if (b.size() >= 8 && std::memcmp(b.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "image/png";
  if (b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) return "image/jpeg";
  if (b.size() >= 12 && std::memcmp(b.data(), "RIFF", 4) == 0 && std::memcmp(b.data() + 8, "WEBP", 4) == 0)
    return "image/webp";
  if (b.size() >= 12 && std::memcmp(b.data(), "\xABKTX 20\xBB\r\n\x1a\n", 12) == 0) return "image/ktx2";
  return "";
}

// An image's bytes live this many times at once while a file is encoded (measured: peak
// memory grows by 4 bytes per image byte; the input's, the model's, the MATL section's and
// the written file's). The budget takes them all before the first copy, so --max-memory bounds
// what an image costs, not only its first copy (tests/cli_hostile_assets_test.cpp).
constexpr uint64_t kImageCopies = 4;

bool take_image(uint64_t bytes, const std::string& what, MemoryBudget* budget, std::string* error) {
  return budget->take(bytes, kImageCopies, what + " (" + std::to_string(bytes) + " bytes, held " +
                                               std::to_string(kImageCopies) + " times while encoding)", error);
}

// An image's bytes: its bufferView's, its data: uri's (tinygltf decoded them into
// image.image, see gltf_load.cpp), or its file's, read under the resource policy.
bool image_bytes(const tinygltf::Model& model, size_t index, const std::string& gltf_dir, const ReadLimits& limits,
                 MemoryBudget* budget, std::vector<uint8_t>* out, std::string* error) {
  const std::string what = "image " + std::to_string(index);
  if (index >= model.images.size()) return fail(error, what + " does not exist");
  const tinygltf::Image& im = model.images[index];
  if (im.bufferView >= 0) {
    if (size_t(im.bufferView) >= model.bufferViews.size()) return fail(error, what + ": its bufferView does not exist");
    const tinygltf::BufferView& v = model.bufferViews[im.bufferView];
    if (v.buffer < 0 || size_t(v.buffer) >= model.buffers.size()) return fail(error, what + ": its buffer does not exist");
    const std::vector<unsigned char>& data = model.buffers[v.buffer].data;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset)
      return fail(error, what + ": its bufferView runs past its buffer");
    if (!take_image(v.byteLength, what, budget, error)) return false;
    out->assign(data.begin() + std::ptrdiff_t(v.byteOffset), data.begin() + std::ptrdiff_t(v.byteOffset + v.byteLength));
    return true;
  }
  if (!im.image.empty()) {
    if (!take_image(im.image.size(), what, budget, error)) return false;
    out->assign(im.image.begin(), im.image.end());
    return true;
  }
  std::string path, err;
  struct stat st;
  if (im.uri.empty() || im.uri.rfind("data:", 0) == 0) return fail(error, what + " has no data");
  if (!resolve_resource(gltf_dir, limits.resource_dirs, im.uri, &path, &err) || !check_input_file(path, &err))
    return fail(error, what + ": " + err);
  if (stat(path.c_str(), &st) != 0) return fail(error, what + ": " + path + ": " + std::strerror(errno));
  if (!take_image(uint64_t(st.st_size), what, budget, error)) return false;
  return read_file(path, out, &err, uint64_t(st.st_size)) || fail(error, what + ": " + err);
}

bool collect_images(const Json& doc, const tinygltf::Model& model, const Renumbering& images, const std::string& gltf_dir,
                    const ReadLimits& limits, MemoryBudget* budget, MaterialSet* out, Json* image_json, std::string* error) {
  const Json& all = array_of(doc, "images");
  for (int64_t old : images.order) {
    MaterialImage image;
    if (!valid_index(old, all) || !image_bytes(model, size_t(old), gltf_dir, limits, budget, &image.bytes, error))
      return valid_index(old, all) ? false : fail(error, "a texture names image " + std::to_string(old) + ", which does not exist");
    const Json& in = all[size_t(old)];
    image.mime_type = in.is_object() && in.contains("mimeType") && in["mimeType"].is_string()
                          ? in["mimeType"].get<std::string>() : sniff_mime(image.bytes);
    if (image.mime_type.empty() || image.mime_type.size() > 64)
      return fail(error, "image " + std::to_string(old) + ": no media type, and its bytes are not PNG, JPEG, WebP or KTX2");
    Json j = {{"mimeType", image.mime_type}};
    if (in.is_object() && in.contains("name") && in["name"].is_string()) j["name"] = in["name"];
    image_json->push_back(j);
    out->images.push_back(std::move(image));
  }
  return true;
}

// The extensions of the input that the carried JSON may use: those of materials and textures.
Json material_extensions(const Json& doc, const char* key) {
  Json out = Json::array();
  for (const Json& e : array_of(doc, key))
    if (e.is_string() && (e.get<std::string>().rfind("KHR_materials_", 0) == 0 ||
                          e.get<std::string>().rfind("KHR_texture_", 0) == 0 ||
                          e.get<std::string>().rfind("EXT_texture_", 0) == 0))
      out.push_back(e);
  return out;
}

}  // namespace

std::set<int64_t> used_images(const Json& doc) {
  std::set<int64_t> textures, images;
  const Json& materials = array_of(doc, "materials");
  for (const Json& mesh : array_of(doc, "meshes")) {
    if (!mesh.is_object()) continue;
    for (const Json& p : array_of(mesh, "primitives")) {
      if (!p.is_object() || !p.contains("material") || !p["material"].is_number_integer()) continue;
      const int64_t m = p["material"].get<int64_t>();
      if (!valid_index(m, materials)) continue;
      Json copy = materials[size_t(m)];
      Renumbering r;
      renumber_texture_refs(&copy, &r);
      textures.insert(r.order.begin(), r.order.end());
    }
  }
  const Json& all = array_of(doc, "textures");
  for (int64_t t : textures) {
    if (!valid_index(t, all) || !all[size_t(t)].is_object()) continue;
    Json texture = all[size_t(t)];
    for_each_image_ref(&texture, [&](Json* ref) { images.insert(ref->get<int64_t>()); });
  }
  return images;
}

bool read_gltf_materials(const Json& doc, const tinygltf::Model& model, const std::vector<int>& materials,
                         const std::string& gltf_dir, const ReadLimits& limits, MemoryBudget* budget, MaterialSet* out,
                         std::vector<int>* renumbered, std::string* error) {
  *out = MaterialSet{};
  renumbered->clear();
  Renumbering used, textures, samplers, images;
  const Json& all_materials = array_of(doc, "materials");
  for (int m : materials) {
    if (m >= 0 && !valid_index(m, all_materials)) return fail(error, "a primitive names material " + std::to_string(m) + ", which does not exist");
    renumbered->push_back(m < 0 ? -1 : int(used.add(m)));
  }
  if (used.order.empty()) return true;
  Json result = {{"materials", Json::array()}, {"textures", Json::array()}, {"samplers", Json::array()}, {"images", Json::array()}};
  for (int64_t m : used.order) {
    Json material = all_materials[size_t(m)];
    renumber_texture_refs(&material, &textures);
    result["materials"].push_back(material);
  }
  const Json& all_textures = array_of(doc, "textures");
  const Json& all_samplers = array_of(doc, "samplers");
  for (int64_t t : textures.order) {
    if (!valid_index(t, all_textures) || !all_textures[size_t(t)].is_object())
      return fail(error, "a material names texture " + std::to_string(t) + ", which does not exist");
    Json texture = all_textures[size_t(t)];
    if (texture.contains("sampler") && texture["sampler"].is_number_integer()) {
      if (!valid_index(texture["sampler"].get<int64_t>(), all_samplers)) return fail(error, "texture " + std::to_string(t) + " names no sampler");
      texture["sampler"] = samplers.add(texture["sampler"].get<int64_t>());
    }
    for_each_image_ref(&texture, [&](Json* ref) { *ref = images.add(ref->get<int64_t>()); });
    result["textures"].push_back(texture);
  }
  for (int64_t s : samplers.order) result["samplers"].push_back(all_samplers[size_t(s)]);
  if (!collect_images(doc, model, images, gltf_dir, limits, budget, out, &result["images"], error)) return false;
  for (const char* key : {"extensionsUsed", "extensionsRequired"})
    if (Json e = material_extensions(doc, key); !e.empty()) result[key] = e;
  out->json = result.dump();
  return true;
}

}  // namespace dcurve
