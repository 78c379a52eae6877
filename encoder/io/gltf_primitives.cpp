#include "encoder/io/gltf_primitives.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/gltf_accessor.h"
#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace {

const char* mode_name(int mode) {
  switch (mode) {
    case TINYGLTF_MODE_POINTS: return "POINTS";
    case TINYGLTF_MODE_LINE: return "LINES";
    case TINYGLTF_MODE_LINE_LOOP: return "LINE_LOOP";
    case TINYGLTF_MODE_LINE_STRIP: return "LINE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_STRIP: return "TRIANGLE_STRIP";
    case TINYGLTF_MODE_TRIANGLE_FAN: return "TRIANGLE_FAN";
    default: return "an unknown mode";
  }
}

uint64_t accessor_count(const tinygltf::Model& model, int index) {
  return index >= 0 && size_t(index) < model.accessors.size() ? model.accessors[index].count : 0;
}

// The static attributes dcurve keeps (codec/common/render_mesh.h); colours may be VEC3 or VEC4.
bool read_attributes(const tinygltf::Model& model, const tinygltf::Primitive& p, MemoryBudget* budget, GltfGeometry* g,
                     std::string* error) {
  for (uint8_t s = 0; s < kAttributeSemanticCount; ++s) {
    const AttributeSemantic semantic = AttributeSemantic(s);
    auto it = p.attributes.find(attribute_gltf_name(semantic));
    if (it == p.attributes.end()) continue;
    uint32_t components = semantic == AttributeSemantic::Normal ? 3 : 2;
    if (semantic == AttributeSemantic::Color0 && it->second >= 0 && size_t(it->second) < model.accessors.size())
      components = model.accessors[it->second].type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    AnimationRender::Attribute a{semantic, components, {}};
    if (!read_float_accessor(model, it->second, int(components), it->first, budget, &a.values, error, true)) return false;
    if (a.values.size() != g->base.size() / 3 * components)
      return fail(error, it->first + ": vertex count differs from POSITION");
    for (float x : a.values)
      if (!std::isfinite(x)) return fail(error, it->first + ": a value is not finite");
    g->attributes.push_back(std::move(a));
  }
  return true;
}

bool read_faces(const tinygltf::Model& model, const tinygltf::Primitive& p, uint32_t vertices, MemoryBudget* budget,
                std::vector<uint32_t>* faces, std::string* error) {
  if (p.indices >= 0) {
    if (!read_index_accessor(model, p.indices, budget, faces, error)) return false;
  } else {
    if (!budget->take(vertices, 4, "indices", error)) return false;
    faces->resize(vertices);
    for (uint32_t v = 0; v < vertices; ++v) (*faces)[v] = v;
  }
  if (faces->size() % 3 != 0) return fail(error, "indices: " + std::to_string(faces->size()) + " is not a multiple of 3");
  for (uint32_t id : *faces)
    if (id >= vertices) return fail(error, "indices: vertex " + std::to_string(id) + " does not exist");
  return true;
}

bool read_targets(const tinygltf::Model& model, const tinygltf::Primitive& p, MemoryBudget* budget, GltfGeometry* g,
                  std::string* error) {
  if (!budget->take(p.targets.size(), sizeof(std::vector<float>), "morph targets", error)) return false;
  g->targets.resize(p.targets.size());
  for (size_t t = 0; t < p.targets.size(); ++t) {
    auto tp = p.targets[t].find("POSITION");
    if (tp == p.targets[t].end()) continue;  // a target that moves no vertex
    const std::string what = "morph target " + std::to_string(t);
    if (!read_float_accessor(model, tp->second, 3, what, budget, &g->targets[t], error)) return false;
    if (g->targets[t].size() != g->base.size()) return fail(error, what + ": vertex count differs from POSITION");
  }
  return true;
}

bool read_primitive(const tinygltf::Model& model, const tinygltf::Primitive& p, const std::string& name,
                    MemoryBudget* budget, GltfGeometry* g, std::string* error) {
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1)
    return fail(error, name + " is " + std::string(mode_name(p.mode)) + ", not TRIANGLES");
  auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) return fail(error, name + " has no POSITION attribute");
  if (!read_float_accessor(model, pos->second, 3, "POSITION", budget, &g->base, error)) return false;
  if (g->base.empty()) return fail(error, name + " has no vertices");
  if (g->base.size() / 3 > UINT32_MAX) return fail(error, name + " has more than 2^32 vertices");
  if (!read_faces(model, p, uint32_t(g->base.size() / 3), budget, &g->faces, error)) return false;
  g->materials = {p.material};
  g->face_primitive.assign(g->faces.size() / 3, 0);
  return read_targets(model, p, budget, g, error) && read_attributes(model, p, budget, g, error);
}

// RGB colours become RGBA with alpha 1, so primitives with either can be joined.
void widen_color(AnimationRender::Attribute* a) {
  if (a->semantic != AttributeSemantic::Color0 || a->components == 4) return;
  std::vector<float> rgba;
  rgba.reserve(a->values.size() / 3 * 4);
  for (size_t i = 0; i < a->values.size(); i += 3) rgba.insert(rgba.end(), {a->values[i], a->values[i + 1], a->values[i + 2], 1.f});
  a->values.swap(rgba);
  a->components = 4;
}

AnimationRender::Attribute* find(std::vector<AnimationRender::Attribute>& list, AttributeSemantic s) {
  for (AnimationRender::Attribute& a : list)
    if (a.semantic == s) return &a;
  return nullptr;
}

// Appends `part`'s values of every attribute either has, zeros where one lacks it.
void join_attributes(GltfGeometry* all, GltfGeometry* part, size_t before, size_t added) {
  for (uint8_t s = 0; s < kAttributeSemanticCount; ++s) {
    AnimationRender::Attribute *a = find(all->attributes, AttributeSemantic(s)), *b = find(part->attributes, AttributeSemantic(s));
    if (!a && !b) continue;
    if (!a) {
      all->attributes.push_back({b->semantic, b->components, std::vector<float>(before * b->components, 0.f)});
      a = &all->attributes.back();
    }
    if (b && a->components != b->components) {
      widen_color(a);
      widen_color(b);
    }
    if (b) a->values.insert(a->values.end(), b->values.begin(), b->values.end());
    else a->values.resize(a->values.size() + added * a->components, 0.f);
  }
  std::sort(all->attributes.begin(), all->attributes.end(),
            [](const auto& x, const auto& y) { return x.semantic < y.semantic; });
}

void join_targets(GltfGeometry* all, const GltfGeometry& part, size_t before) {
  for (size_t t = 0; t < part.targets.size(); ++t) {
    std::vector<float>& a = all->targets[t];
    const std::vector<float>& b = part.targets[t];
    if (a.empty() && b.empty()) continue;  // still moves nothing
    a.resize(3 * before, 0.f);
    if (b.empty()) a.resize(a.size() + part.base.size(), 0.f);
    else a.insert(a.end(), b.begin(), b.end());
  }
}

void join(GltfGeometry* all, GltfGeometry* part) {
  const size_t before = all->base.size() / 3, added = part->base.size() / 3;
  const uint32_t primitive = uint32_t(all->materials.size());
  for (uint32_t id : part->faces) all->faces.push_back(uint32_t(before) + id);
  all->face_primitive.insert(all->face_primitive.end(), part->faces.size() / 3, primitive);
  all->materials.push_back(part->materials[0]);
  join_targets(all, *part, before);
  join_attributes(all, part, before, added);
  all->base.insert(all->base.end(), part->base.begin(), part->base.end());
}

}  // namespace

bool read_gltf_geometry(const tinygltf::Model& model, const tinygltf::Mesh& mesh, MemoryBudget* budget, GltfGeometry* g,
                        std::string* error) {
  const std::string name = "mesh '" + quote_file_text(mesh.name, 40) + "'";
  if (mesh.primitives.empty()) return fail(error, name + " has no primitives");
  *g = GltfGeometry{};
  for (size_t i = 0; i < mesh.primitives.size(); ++i) {
    const std::string what = name + (mesh.primitives.size() > 1 ? ", primitive " + std::to_string(i) : ": its primitive");
    GltfGeometry part;
    if (!read_primitive(model, mesh.primitives[i], what, budget, &part, error)) return false;
    if (i == 0) g->targets.resize(part.targets.size());
    else if (part.targets.size() != g->targets.size())
      return fail(error, what + " has " + std::to_string(part.targets.size()) + " morph targets, primitive 0 " +
                             std::to_string(g->targets.size()) + " (glTF requires the same count)");
    join(g, &part);
  }
  if (g->base.size() / 3 > UINT32_MAX) return fail(error, name + " has more than 2^32 vertices");
  if (g->targets.empty()) return fail(error, name + " has no morph targets (dcurve reads morph-target animation)");
  return true;
}

long double gltf_declared_bytes(const tinygltf::Model& model, const tinygltf::Mesh& mesh, uint64_t keys,
                                uint64_t* vertices, uint64_t* targets) {
  long double v = 0, indices = 0;
  size_t arrays = 1;  // POSITION
  for (const tinygltf::Primitive& p : mesh.primitives) {
    auto pos = p.attributes.find("POSITION");
    v += pos == p.attributes.end() ? 0 : accessor_count(model, pos->second);
    indices += accessor_count(model, p.indices);
    size_t with_position = 1;
    for (const auto& target : p.targets) with_position += target.count("POSITION");
    arrays = std::max(arrays, with_position);
  }
  *vertices = uint64_t(std::min(v, 1e19L));
  *targets = arrays - 1;
  // The joined arrays (a target some primitive moves is stored for all) and the frames.
  return 12 * v * (arrays + keys) + 4 * indices;
}

}  // namespace dcurve
