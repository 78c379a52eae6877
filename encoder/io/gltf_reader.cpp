#include "encoder/io/gltf_reader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frame_times.h"
#include "encoder/io/gltf_accessor.h"
#include "encoder/io/gltf_load.h"
#include "encoder/io/gltf_placement.h"
#include "encoder/io/quoted_text.h"
#include "encoder/io/weld.h"

namespace dcurve {
namespace {

// Compression extensions change what the buffers hold; reading through them would give garbage.
bool check_extensions(const tinygltf::Model& model, std::string* error) {
  std::vector<std::string> used = model.extensionsUsed;
  used.insert(used.end(), model.extensionsRequired.begin(), model.extensionsRequired.end());
  for (const std::string& e : used)
    if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
      return fail(error, "uses " + quote_file_text(e) +
                             ", which dcurve does not decode (supported: uncompressed and sparse accessors; "
                             "not Draco or meshopt compression): export without mesh compression");
  for (const std::string& e : model.extensionsRequired)
    if (e != "KHR_materials_unlit" && e != "KHR_texture_transform" && e != "KHR_mesh_quantization")
      return fail(error, "requires the extension " + quote_file_text(e) + ", which dcurve does not read");
  return true;
}

bool choose_mesh(const tinygltf::Model& model, int mesh_index, int* chosen, std::string* error) {
  if (model.meshes.empty()) return fail(error, "holds no mesh");
  if (mesh_index >= 0) {
    if (size_t(mesh_index) >= model.meshes.size())
      return fail(error, "has no mesh " + std::to_string(mesh_index) + " (it holds " + std::to_string(model.meshes.size()) + ")");
    *chosen = mesh_index;
    return true;
  }
  if (model.meshes.size() > 1) {
    std::string names;
    for (size_t m = 0; m < model.meshes.size(); ++m)
      names += (m ? ", " : "") + std::to_string(m) + " '" + quote_file_text(model.meshes[m].name, 40) + "'";
    return fail(error, "holds " + std::to_string(model.meshes.size()) + " meshes (" + names +
                           "); dcurve encodes one: choose it with --gltf-mesh INDEX");
  }
  *chosen = 0;
  return true;
}

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

// The base positions, faces and morph targets of the mesh's one triangle primitive. A target
// that moves no vertex is an empty array, so many of them cost nothing.
struct Geometry {
  std::vector<float> base;
  std::vector<uint32_t> faces;
  std::vector<std::vector<float>> targets;
  std::vector<AnimationRender::Attribute> attributes;
};

// The static attributes dcurve keeps (codec/common/render_mesh.h); colours may be VEC3 or VEC4.
bool read_attributes(const tinygltf::Model& model, const tinygltf::Primitive& p, MemoryBudget* budget, Geometry* g,
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

bool read_targets(const tinygltf::Model& model, const tinygltf::Primitive& p, MemoryBudget* budget, Geometry* g,
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

bool read_geometry(const tinygltf::Model& model, const tinygltf::Mesh& mesh, MemoryBudget* budget, Geometry* g,
                   std::string* error) {
  const std::string name = "mesh '" + quote_file_text(mesh.name, 40) + "'";
  if (mesh.primitives.size() != 1)
    return fail(error, name + " has " + std::to_string(mesh.primitives.size()) + " primitives; dcurve reads one");
  const tinygltf::Primitive& p = mesh.primitives[0];
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1)
    return fail(error, name + ": its primitive is " + std::string(mode_name(p.mode)) + ", not TRIANGLES");
  auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) return fail(error, name + " has no POSITION attribute");
  if (!read_float_accessor(model, pos->second, 3, "POSITION", budget, &g->base, error)) return false;
  if (g->base.empty()) return fail(error, name + " has no vertices");
  if (g->base.size() / 3 > UINT32_MAX) return fail(error, name + " has more than 2^32 vertices");
  if (!read_faces(model, p, uint32_t(g->base.size() / 3), budget, &g->faces, error)) return false;
  if (p.targets.empty()) return fail(error, name + " has no morph targets (dcurve reads morph-target animation)");
  return read_targets(model, p, budget, g, error) && read_attributes(model, p, budget, g, error);
}

// The one channel that animates the weights of a node showing mesh `mesh`.
struct WeightsChannel {
  const tinygltf::AnimationSampler* sampler = nullptr;
  int node = -1, animation = -1, channel = -1;
};

bool find_weights_sampler(const tinygltf::Model& model, int mesh, WeightsChannel* out, std::string* error) {
  int found = 0;
  for (size_t a = 0; a < model.animations.size(); ++a)
    for (size_t c = 0; c < model.animations[a].channels.size(); ++c) {
      const tinygltf::Animation& anim = model.animations[a];
      const tinygltf::AnimationChannel& ch = anim.channels[c];
      const bool ours = ch.target_node >= 0 && size_t(ch.target_node) < model.nodes.size() &&
                        model.nodes[ch.target_node].mesh == mesh && ch.target_path == "weights";
      if (!ours) continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) return fail(error, "animation channel with no sampler");
      *out = {&anim.samplers[ch.sampler], ch.target_node, int(a), int(c)};
      ++found;
    }
  if (found == 0)
    return fail(error, "has no animation of mesh " + std::to_string(mesh) +
                           "'s morph-target weights (dcurve reads vertex animation as morph targets driven by weights)");
  if (found > 1)
    return fail(error, std::to_string(found) + " animation channels drive mesh " + std::to_string(mesh) +
                           "'s weights; dcurve reads one (export one animation)");
  return true;
}

// Frames per second from the key times (frame_times.h).
bool key_frame_rate(const std::vector<float>& times, double* fps, std::string* error) {
  return frame_rate_from_times(std::vector<double>(times.begin(), times.end()), "the weights animation's key times", fps,
                               error);
}

bool read_keys(const tinygltf::Model& model, const tinygltf::AnimationSampler& s, size_t targets, MemoryBudget* budget,
               std::vector<float>* times, std::vector<float>* weights, std::string* error) {
  if (!read_float_accessor(model, s.input, 1, "animation input (times)", budget, times, error) ||
      !read_float_accessor(model, s.output, 1, "animation output (weights)", budget, weights, error))
    return false;
  const size_t per_key = s.interpolation == "CUBICSPLINE" ? 3 * targets : targets;
  if (weights->size() != times->size() * per_key)
    return fail(error, "the weights animation has " + std::to_string(weights->size()) + " values for " +
                           std::to_string(times->size()) + " keys of " + std::to_string(targets) + " targets");
  if (per_key != targets) {  // cubic spline keys are (in-tangent, value, out-tangent): keep the values
    std::vector<float> values;
    for (size_t k = 0; k < times->size(); ++k)
      values.insert(values.end(), weights->begin() + k * per_key + targets, weights->begin() + k * per_key + 2 * targets);
    *weights = std::move(values);
  }
  return true;
}

bool blend_frames(const Geometry& g, const std::vector<float>& weights, size_t keys, MemoryBudget* budget, Animation* anim,
                  std::string* error) {
  const size_t targets = g.targets.size();
  if (!budget->take(keys, g.base.size() * sizeof(float), "the frames (" + std::to_string(keys) + " keys)", error))
    return false;
  anim->frames.assign(keys, g.base);
  for (size_t k = 0; k < keys; ++k)
    for (size_t t = 0; t < targets; ++t) {
      const float w = weights[k * targets + t];
      if (w == 0.0f || g.targets[t].empty()) continue;
      std::vector<float>& f = anim->frames[k];
      for (size_t i = 0; i < f.size(); ++i) f[i] += w * g.targets[t][i];
    }
  return true;
}

uint64_t accessor_count(const tinygltf::Model& model, int index) {
  return index >= 0 && size_t(index) < model.accessors.size() ? model.accessors[index].count : 0;
}

// What the mesh's arrays and frames will take, from the accessors' counts alone: refused
// before the first of them is allocated, however the file spreads its size over them.
bool check_declared_size(const tinygltf::Model& model, const tinygltf::Mesh& mesh, const tinygltf::AnimationSampler& s,
                         const MemoryBudget& budget, std::string* error) {
  if (mesh.primitives.size() != 1) return true;  // refused by read_geometry
  const tinygltf::Primitive& p = mesh.primitives[0];
  auto pos = p.attributes.find("POSITION");
  const long double vertices = pos == p.attributes.end() ? 0 : accessor_count(model, pos->second);
  long double arrays = 1;  // POSITION
  for (const auto& target : p.targets) arrays += target.count("POSITION");
  const long double keys = accessor_count(model, s.input);
  const long double bytes = 12 * vertices * (arrays + keys) + 4.0L * accessor_count(model, p.indices) +
                            4.0L * (keys + accessor_count(model, s.output));
  if (bytes > 1e19L || !budget.fits(uint64_t(bytes), 1))
    return fail(error, "POSITION, the morph targets and the keys declare " + std::to_string(uint64_t(vertices)) + " vertices, " +
                           std::to_string(uint64_t(arrays - 1)) + " morph targets and " + std::to_string(uint64_t(keys)) +
                           " keys: more than the memory limit allows (--max-memory)");
  return true;
}

bool read_model_animation(const tinygltf::Model& model, int mesh_index, MemoryBudget* budget, Animation* anim,
                          std::string* error) {
  int mesh = 0;
  Geometry g;
  WeightsChannel channel;
  std::vector<float> times, weights;
  if (!check_extensions(model, error) || !choose_mesh(model, mesh_index, &mesh, error) ||
      !find_weights_sampler(model, mesh, &channel, error) ||
      !check_declared_size(model, model.meshes[mesh], *channel.sampler, *budget, error) ||
      !read_geometry(model, model.meshes[mesh], budget, &g, error) ||
      !read_keys(model, *channel.sampler, g.targets.size(), budget, &times, &weights, error) ||
      !key_frame_rate(times, &anim->frame_rate, error))
    return false;
  anim->vertex_count = uint32_t(g.base.size() / 3);
  anim->faces = std::move(g.faces);
  anim->placement = gltf_placement(model, channel.node, mesh);
  anim->placement.start_time = times.empty() ? 0.0 : double(times[0]);
  anim->notes = gltf_dropped_animations(model, channel.animation, channel.channel);
  if (!blend_frames(g, weights, times.size(), budget, anim, error)) return false;
  // Frames first: welding compares every frame; a degenerate triangle it leaves is dropped.
  weld_copies(anim, std::move(g.attributes));
  return validate_animation(*anim, error);
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

bool read_gltf_animation(const std::string& path, int mesh_index, Animation* anim, std::string* error,
                         const ReadLimits& limits) {
  tinygltf::Model model;
  *anim = Animation{};
  std::string err;
  MemoryBudget budget(limits.max_memory);
  if (!load_gltf_model(path, limits, &budget, &model, &err) ||
      !read_model_animation(model, mesh_index, &budget, anim, &err))
    return fail(error, path + ": " + err);
  return true;
}

}  // namespace dcurve
