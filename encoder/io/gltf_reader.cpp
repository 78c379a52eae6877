#include "encoder/io/gltf_reader.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/gltf_accessor.h"

namespace dcurve {
namespace {

// dcurve reads geometry only: images are neither decoded nor required to exist.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

bool load_model(const std::string& path, tinygltf::Model* model, std::string* error) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skip_image, nullptr);
  std::string err, warn;
  const bool ok = lowercase_extension(path) == ".glb" ? loader.LoadBinaryFromFile(model, &err, &warn, path)
                                                      : loader.LoadASCIIFromFile(model, &err, &warn, path);
  while (!err.empty() && std::isspace(static_cast<unsigned char>(err.back()))) err.pop_back();  // tinygltf ends lines with \n
  if (!ok) return fail(error, "cannot read glTF: " + (err.empty() ? std::string("malformed file") : err));
  return true;
}

// Compression extensions change what the buffers hold; reading through them would give garbage.
bool check_extensions(const tinygltf::Model& model, std::string* error) {
  std::vector<std::string> used = model.extensionsUsed;
  used.insert(used.end(), model.extensionsRequired.begin(), model.extensionsRequired.end());
  for (const std::string& e : used)
    if (e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression" || e == "KHR_meshopt_compression")
      return fail(error, "uses " + e +
                             ", which dcurve does not decode (supported: uncompressed and sparse accessors; "
                             "not Draco or meshopt compression): export without mesh compression");
  for (const std::string& e : model.extensionsRequired)
    if (e != "KHR_materials_unlit" && e != "KHR_texture_transform" && e != "KHR_mesh_quantization")
      return fail(error, "requires the extension " + e + ", which dcurve does not read");
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
      names += (m ? ", " : "") + std::to_string(m) + " '" + model.meshes[m].name + "'";
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

// The base positions, faces and morph targets of the mesh's one triangle primitive.
struct Geometry {
  std::vector<float> base;
  std::vector<uint32_t> faces;
  std::vector<std::vector<float>> targets;
};

bool read_faces(const tinygltf::Model& model, const tinygltf::Primitive& p, uint32_t vertices, std::vector<uint32_t>* faces,
                std::string* error) {
  if (p.indices >= 0) {
    if (!read_index_accessor(model, p.indices, faces, error)) return false;
  } else {
    faces->resize(vertices);
    for (uint32_t v = 0; v < vertices; ++v) (*faces)[v] = v;
  }
  if (faces->size() % 3 != 0) return fail(error, "indices: " + std::to_string(faces->size()) + " is not a multiple of 3");
  for (uint32_t id : *faces)
    if (id >= vertices) return fail(error, "indices: vertex " + std::to_string(id) + " does not exist");
  return true;
}

bool read_geometry(const tinygltf::Model& model, const tinygltf::Mesh& mesh, Geometry* g, std::string* error) {
  const std::string name = "mesh '" + mesh.name + "'";
  if (mesh.primitives.size() != 1)
    return fail(error, name + " has " + std::to_string(mesh.primitives.size()) + " primitives; dcurve reads one");
  const tinygltf::Primitive& p = mesh.primitives[0];
  if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1)
    return fail(error, name + ": its primitive is " + std::string(mode_name(p.mode)) + ", not TRIANGLES");
  auto pos = p.attributes.find("POSITION");
  if (pos == p.attributes.end()) return fail(error, name + " has no POSITION attribute");
  if (!read_float_accessor(model, pos->second, 3, "POSITION", &g->base, error)) return false;
  if (g->base.empty()) return fail(error, name + " has no vertices");
  if (!read_faces(model, p, uint32_t(g->base.size() / 3), &g->faces, error)) return false;
  if (p.targets.empty()) return fail(error, name + " has no morph targets (dcurve reads morph-target animation)");
  for (size_t t = 0; t < p.targets.size(); ++t) {
    g->targets.emplace_back(g->base.size(), 0.0f);
    auto tp = p.targets[t].find("POSITION");
    if (tp == p.targets[t].end()) continue;  // a target that moves no vertex
    const std::string what = "morph target " + std::to_string(t);
    if (!read_float_accessor(model, tp->second, 3, what, &g->targets[t], error)) return false;
    if (g->targets[t].size() != g->base.size()) return fail(error, what + ": vertex count differs from POSITION");
  }
  return true;
}

// The one sampler that animates the weights of a node showing mesh `mesh`.
bool find_weights_sampler(const tinygltf::Model& model, int mesh, const tinygltf::AnimationSampler** sampler,
                          std::string* error) {
  int found = 0;
  for (const auto& anim : model.animations)
    for (const auto& ch : anim.channels) {
      const bool ours = ch.target_node >= 0 && size_t(ch.target_node) < model.nodes.size() &&
                        model.nodes[ch.target_node].mesh == mesh && ch.target_path == "weights";
      if (!ours) continue;
      if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) return fail(error, "animation channel with no sampler");
      *sampler = &anim.samplers[ch.sampler];
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

// Frames per second from evenly spaced key times.
bool key_frame_rate(const std::vector<float>& times, double* fps, std::string* error) {
  if (times.empty()) return fail(error, "the weights animation has no keys");
  if (times.size() < 2) return true;
  const double dt = (double(times.back()) - times.front()) / double(times.size() - 1);
  if (!(dt > 0)) return fail(error, "the weights animation's key times do not increase");
  for (size_t i = 0; i < times.size(); ++i)
    if (std::abs(times[i] - (times.front() + dt * double(i))) > 0.01 * dt)
      return fail(error, "the weights animation's keys are not evenly spaced (key " + std::to_string(i) + " at " +
                             std::to_string(times[i]) + " s); dcurve needs one key per frame");
  *fps = 1.0 / dt;
  return true;
}

bool read_keys(const tinygltf::Model& model, const tinygltf::AnimationSampler& s, size_t targets,
               std::vector<float>* times, std::vector<float>* weights, std::string* error) {
  if (!read_float_accessor(model, s.input, 1, "animation input (times)", times, error) ||
      !read_float_accessor(model, s.output, 1, "animation output (weights)", weights, error))
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

void blend_frames(const Geometry& g, const std::vector<float>& weights, size_t keys, Animation* anim) {
  const size_t targets = g.targets.size();
  anim->frames.assign(keys, g.base);
  for (size_t k = 0; k < keys; ++k)
    for (size_t t = 0; t < targets; ++t) {
      const float w = weights[k * targets + t];
      if (w == 0.0f) continue;
      std::vector<float>& f = anim->frames[k];
      for (size_t i = 0; i < f.size(); ++i) f[i] += w * g.targets[t][i];
    }
}

bool read_model_animation(const tinygltf::Model& model, int mesh_index, Animation* anim, std::string* error) {
  int mesh = 0;
  Geometry g;
  const tinygltf::AnimationSampler* sampler = nullptr;
  std::vector<float> times, weights;
  if (!check_extensions(model, error) || !choose_mesh(model, mesh_index, &mesh, error) ||
      !read_geometry(model, model.meshes[mesh], &g, error) || !find_weights_sampler(model, mesh, &sampler, error) ||
      !read_keys(model, *sampler, g.targets.size(), &times, &weights, error) ||
      !key_frame_rate(times, &anim->frame_rate, error))
    return false;
  anim->vertex_count = uint32_t(g.base.size() / 3);
  anim->faces = std::move(g.faces);
  blend_frames(g, weights, times.size(), anim);
  return validate_animation(*anim, error);
}

}  // namespace

bool is_gltf_path(const std::string& path) {
  const std::string ext = lowercase_extension(path);
  return ext == ".gltf" || ext == ".glb";
}

bool read_gltf_animation(const std::string& path, int mesh_index, Animation* anim, std::string* error) {
  tinygltf::Model model;
  *anim = Animation{};
  std::string err;
  if (!load_model(path, &model, &err) || !read_model_animation(model, mesh_index, anim, &err))
    return fail(error, path + ": " + err);
  return true;
}

}  // namespace dcurve
