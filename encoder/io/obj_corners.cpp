#include "encoder/io/obj_corners.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"

namespace dcurve {
namespace {

struct Corner {
  int64_t v = -1, vt = -1, vn = -1;
};

// An OBJ index (1-based, or negative: counted back from the last one read) as 0-based.
bool resolve(const std::string& text, size_t count, int64_t* out) {
  char* end = nullptr;
  const long long i = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || i == 0) return false;
  const long long r = i > 0 ? i - 1 : (long long)count + i;
  if (r < 0 || size_t(r) >= count) return false;
  *out = r;
  return true;
}

bool parse_corner(const std::string& token, const size_t counts[3], Corner* c) {
  std::string part[3];
  size_t k = 0;
  for (char ch : token) {
    if (ch == '/') {
      if (++k > 2) return false;
    } else {
      part[k] += ch;
    }
  }
  if (!resolve(part[0], counts[0], &c->v)) return false;
  if (!part[1].empty() && !resolve(part[1], counts[1], &c->vt)) return false;
  return part[2].empty() || resolve(part[2], counts[2], &c->vn);
}

struct Reader {
  ObjCorners* out;
  size_t counts[3] = {0, 0, 0};  // v, vt, vn read so far
  int32_t material = -1;

  void use_material(const std::string& name) {
    auto it = std::find(out->materials.begin(), out->materials.end(), name);
    material = int32_t(it - out->materials.begin());
    if (it == out->materials.end()) out->materials.push_back(name);
  }

  void add_polygon(const std::vector<Corner>& p) {
    for (size_t k = 1; k + 1 < p.size(); ++k) {
      for (const Corner* c : {&p[0], &p[k], &p[k + 1]}) {
        out->vertex.push_back(uint32_t(c->v));
        out->texcoord.push_back(c->vt);
        out->normal.push_back(c->vn);
      }
      out->face_material.push_back(material);
    }
  }

  bool line(std::istringstream& in, const std::string& key) {
    float x = 0, y = 0, z = 0;
    if (key == "v") ++counts[0];
    else if (key == "vt") {
      in >> x >> y;
      out->texcoords.insert(out->texcoords.end(), {x, y});
      ++counts[1];
    } else if (key == "vn") {
      in >> x >> y >> z;
      out->normals.insert(out->normals.end(), {x, y, z});
      ++counts[2];
    } else if (key == "usemtl") {
      std::string name;
      in >> name;
      use_material(name);
    } else if (key == "mtllib" && out->material_library.empty()) {
      in >> out->material_library;
    } else if (key == "f") {
      std::vector<Corner> p;
      for (std::string token; in >> token;) {
        p.emplace_back();
        if (!parse_corner(token, counts, &p.back())) return false;
      }
      add_polygon(p);
    }
    return true;
  }
};

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

bool read_obj_corners(const std::string& path, ObjCorners* out, std::string* error) {
  *out = ObjCorners{};
  std::vector<uint8_t> bytes;
  if (!read_file(path, &bytes, error)) return false;
  std::istringstream text(std::string(bytes.begin(), bytes.end()));
  Reader reader{out};
  size_t number = 0;
  for (std::string line; std::getline(text, line);) {
    ++number;
    std::istringstream in(line);
    std::string key;
    if (!(in >> key)) continue;
    if (!reader.line(in, key))
      return fail(error, path + ": line " + std::to_string(number) + ": a face corner is malformed or out of range");
  }
  return true;
}

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
