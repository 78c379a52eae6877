#include "corpus/input.h"

#include <filesystem>

#include "codec/common/error.h"
#include "encoder/io/frame_times.h"
#include "encoder/io/gltf_reader.h"
#include "encoder/io/point_cache.h"
#include "corpus/sim/scene.h"

namespace dcurve {

bool load_animation_input(const std::string& input, bool allow_builtin, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec)) return read_frame_folder(input, anim, error, progress);
  Scene scene;
  std::string err;
  if (std::filesystem::is_regular_file(input, ec)) {
    if (!load_scene_file(input, &scene, &err)) {
      if (error) *error = err;
      return false;
    }
  } else if (!allow_builtin || !builtin_scene(input, &scene, &err)) {
    if (error) *error = input + ": no such file or folder" + (allow_builtin ? ", nor a built-in scene" : "");
    return false;
  }
  if (!simulate_scene(scene, anim, progress, &err)) {
    if (error) *error = input + ": " + err;
    return false;
  }
  return true;
}

namespace {

// A point cache's positions with the faces of its rest mesh.
bool load_point_cache(const std::string& input, const std::string& rest_mesh, uint64_t max_memory, Animation* anim,
                      PointCacheInfo* info, std::string* error) {
  if (rest_mesh.empty())
    return fail(error, input + ": a point cache holds positions only: give the faces with --mesh REST.obj");
  if (!read_point_cache(input, anim, info, error, max_memory)) return false;
  std::vector<float> rest;
  if (!read_mesh(rest_mesh, &rest, &anim->faces, error)) return false;
  if (rest.size() != size_t(anim->vertex_count) * 3)
    return fail(error, rest_mesh + ": " + std::to_string(rest.size() / 3) + " vertices, but " + input + " has " +
                           std::to_string(anim->vertex_count));
  return validate_animation(*anim, error);
}

}  // namespace

std::string input_stage_label(const std::string& input) {
  std::error_code ec;
  PointCacheKind kind;
  const bool read = std::filesystem::is_directory(input, ec) || is_gltf_path(input) || point_cache_kind(input, &kind);
  return read ? "read" : "simulate";
}

bool load_animation_input(const std::string& input, const InputOptions& options, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error) {
  PointCacheKind kind;
  const bool cache = point_cache_kind(input, &kind);
  if (!options.rest_mesh.empty() && !cache)
    return fail(error, input + ": --mesh is for point caches (.pc2, .mdd) only");
  if (options.gltf_mesh >= 0 && !is_gltf_path(input)) return fail(error, input + ": --gltf-mesh is for glTF files only");
  bool ok;
  PointCacheInfo info;
  if (cache)
    ok = load_point_cache(input, options.rest_mesh, options.limits.max_memory, anim, &info, error);
  else if (is_gltf_path(input))
    ok = read_gltf_animation(input, options.gltf_mesh, anim, error, options.limits);
  else
    ok = load_animation_input(input, false, progress, anim, error);
  if (ok && options.fps > 0) anim->frame_rate = options.fps;
  // The first frame's time: MDD states it in seconds, PC2 as a frame number at the clip's rate.
  if (ok && cache) anim->placement.start_time = kind == PointCacheKind::Pc2 ? info.start / anim->frame_rate : info.start;
  return ok && check_start_time(anim->placement.start_time, anim->frame_rate, anim->frames.size(),
                                input + ": the first frame's time", error);
}

}  // namespace dcurve
