#include "encoder/io/obj_corners.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "codec/common/error.h"

namespace dcurve {
namespace {

using CopyKey = std::tuple<uint32_t, int64_t, int64_t>;  // vertex, vt, vn

// The render vertices: each vertex's distinct (vt, vn) pairs in order of first use, vertex
// after vertex (so vertices appear in first-use order); a vertex no face uses gets one.
std::vector<CopyKey> render_keys(const ObjCorners& c, uint32_t vertex_count) {
  std::map<CopyKey, size_t> first_use;
  for (size_t k = 0; k < c.vertex.size(); ++k) first_use.emplace(CopyKey{c.vertex[k], c.texcoord[k], c.normal[k]}, k);
  std::vector<std::pair<CopyKey, size_t>> order(first_use.begin(), first_use.end());
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return std::get<0>(a.first) != std::get<0>(b.first) ? std::get<0>(a.first) < std::get<0>(b.first) : a.second < b.second;
  });
  std::vector<CopyKey> keys;
  size_t i = 0;
  for (uint32_t v = 0; v < vertex_count; ++v) {
    if (i == order.size() || std::get<0>(order[i].first) != v) keys.push_back({v, -1, -1});
    while (i < order.size() && std::get<0>(order[i].first) == v) keys.push_back(order[i++].first);
  }
  return keys;
}

void add_attributes(const ObjCorners& c, const std::vector<CopyKey>& keys, AnimationRender* r) {
  if (!c.texcoords.empty()) {
    AnimationRender::Attribute uv{AttributeSemantic::TexCoord0, 2, {}};
    for (const CopyKey& k : keys) {
      const int64_t t = std::get<1>(k);
      // glTF's v runs down the image, OBJ's up.
      uv.values.insert(uv.values.end(), {t < 0 ? 0.f : c.texcoords[2 * t], t < 0 ? 0.f : 1.f - c.texcoords[2 * t + 1]});
    }
    r->attributes.push_back(std::move(uv));
  }
  if (!c.normals.empty()) {
    AnimationRender::Attribute n{AttributeSemantic::Normal, 3, {}};
    for (const CopyKey& k : keys)
      for (int a = 0; a < 3; ++a) n.values.push_back(std::get<2>(k) < 0 ? 0.f : c.normals[3 * std::get<2>(k) + a]);
    r->attributes.push_back(std::move(n));
  }
}

// One group per usemtl name used (and one without a material for faces before any), the
// names as glTF materials and the library's file name beside them.
void add_groups(const ObjCorners& c, Animation* anim) {
  if (c.materials.empty()) return;
  const bool unnamed = std::find(c.face_material.begin(), c.face_material.end(), -1) != c.face_material.end();
  AnimationRender& r = anim->render;
  if (unnamed) r.groups.push_back({-1, ""});
  nlohmann::json materials = nlohmann::json::array();
  for (size_t m = 0; m < c.materials.size(); ++m) {
    r.groups.push_back({int32_t(m), c.materials[m]});
    materials.push_back({{"name", c.materials[m]}});
  }
  for (int32_t m : c.face_material) r.face_group.push_back(uint32_t(m + (unnamed ? 1 : 0)));
  nlohmann::json doc = {{"materials", materials}};
  if (!c.material_library.empty()) doc["objMaterialLibrary"] = c.material_library;
  anim->materials.json = doc.dump();
}

}  // namespace

bool obj_render(const ObjCorners& c, Animation* anim, std::string* error) {
  if (c.texcoords.empty() && c.normals.empty() && c.materials.empty()) return true;
  if (c.vertex != anim->faces) return fail(error, "the OBJ's face corners disagree with its faces");
  const std::vector<CopyKey> keys = render_keys(c, anim->vertex_count);
  std::map<CopyKey, uint32_t> id;
  AnimationRender& r = anim->render;
  for (const CopyKey& k : keys) {
    id.emplace(k, uint32_t(r.source.size()));
    r.source.push_back(std::get<0>(k));
  }
  for (size_t k = 0; k < c.vertex.size(); ++k) r.corners.push_back(id[CopyKey{c.vertex[k], c.texcoord[k], c.normal[k]}]);
  add_attributes(c, keys, &r);
  add_groups(c, anim);
  return true;
}

std::string obj_material_library(const std::string& materials_json) {
  const nlohmann::json m = nlohmann::json::parse(materials_json, nullptr, false);
  if (!m.is_object() || !m.contains("objMaterialLibrary") || !m["objMaterialLibrary"].is_string()) return "";
  return m["objMaterialLibrary"].get<std::string>();
}

}  // namespace dcurve
