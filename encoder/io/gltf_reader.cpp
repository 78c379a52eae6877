#include "encoder/io/gltf_reader.h"

#include <tiny_gltf.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frame_times.h"
#include "encoder/io/gltf_accessor.h"
#include "encoder/io/gltf_load.h"
#include "encoder/io/gltf_materials.h"
#include "encoder/io/gltf_placement.h"
#include "encoder/io/gltf_primitives.h"
#include "encoder/io/quoted_text.h"
#include "encoder/io/weld.h"

namespace dcurve {
namespace {

// Compression extensions change what the buffers hold; reading through them would give garbage.
// What the reader needs of the file besides tinygltf's model.
struct GltfSource {
  int mesh_index;
  std::string dir;  // the glTF's folder: where its images may be
  const ReadLimits& limits;
  std::string json;  // its JSON text: materials are carried as written
};

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

bool blend_frames(const GltfGeometry& g, const std::vector<float>& weights, size_t keys, MemoryBudget* budget, Animation* anim,
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

// What the mesh's arrays and frames will take, from the accessors' counts alone: refused
// before the first of them is allocated, however the file spreads its size over them.
bool check_declared_size(const tinygltf::Model& model, const tinygltf::Mesh& mesh, const tinygltf::AnimationSampler& s,
                         const MemoryBudget& budget, std::string* error) {
  auto count = [&](int i) { return i >= 0 && size_t(i) < model.accessors.size() ? model.accessors[i].count : 0; };
  uint64_t vertices = 0, targets = 0;
  const uint64_t keys = count(s.input);
  const long double bytes = gltf_declared_bytes(model, mesh, keys, &vertices, &targets) + 4.0L * (keys + count(s.output));
  if (bytes > 1e19L || !budget.fits(uint64_t(bytes), 1))
    return fail(error, "POSITION, the morph targets and the keys declare " + std::to_string(vertices) + " vertices, " +
                           std::to_string(targets) + " morph targets and " + std::to_string(keys) +
                           " keys: more than the memory limit allows (--max-memory)");
  return true;
}

// Groups (one per primitive) and their materials, when the mesh has several primitives or a
// material: what a game needs to draw it as exported.
bool read_groups(const tinygltf::Model& model, const std::string& json, const GltfGeometry& g, const std::string& dir,
                 const ReadLimits& limits, MemoryBudget* budget, Animation* anim, std::string* error) {
  if (g.materials.size() == 1 && g.materials[0] < 0) return true;
  const nlohmann::json doc = nlohmann::json::parse(json, nullptr, false);
  std::vector<int> renumbered;
  if (!read_gltf_materials(doc, model, g.materials, dir, limits, budget, &anim->materials, &renumbered, error))
    return false;
  for (size_t p = 0; p < g.materials.size(); ++p) {
    const int m = g.materials[p];
    anim->render.groups.push_back({renumbered[p], m >= 0 ? model.materials[size_t(m)].name : std::string()});
  }
  anim->render.face_group = g.face_primitive;
  return true;
}

bool read_model_animation(const tinygltf::Model& model, const GltfSource& source, MemoryBudget* budget,
                          Animation* anim, std::string* error) {
  int mesh = 0;
  GltfGeometry g;
  WeightsChannel channel;
  std::vector<float> times, weights;
  if (!check_extensions(model, error) || !choose_mesh(model, source.mesh_index, &mesh, error) ||
      !find_weights_sampler(model, mesh, &channel, error) ||
      !check_declared_size(model, model.meshes[mesh], *channel.sampler, *budget, error) ||
      !read_gltf_geometry(model, model.meshes[mesh], budget, &g, error) ||
      !read_keys(model, *channel.sampler, g.targets.size(), budget, &times, &weights, error) ||
      !key_frame_rate(times, &anim->frame_rate, error))
    return false;
  anim->vertex_count = uint32_t(g.base.size() / 3);
  anim->faces = g.faces;
  anim->placement = gltf_placement(model, channel.node, mesh);
  anim->placement.start_time = times.empty() ? 0.0 : double(times[0]);
  anim->notes = gltf_dropped_animations(model, channel.animation, channel.channel);
  if (!read_groups(model, source.json, g, source.dir, source.limits, budget, anim, error) ||
      !blend_frames(g, weights, times.size(), budget, anim, error))
    return false;
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
  GltfSource source{mesh_index, std::filesystem::path(path).parent_path().string(), limits, {}};
  if (!load_gltf_model(path, limits, &budget, &model, &err, &source.json) ||
      !read_model_animation(model, source, &budget, anim, &err))
    return fail(error, path + ": " + err);
  return true;
}

}  // namespace dcurve
