#include "encoder/input.h"

#include <filesystem>

#include "encoder/sim/scene.h"

namespace dcurve {

bool load_animation_input(const std::string& input, bool allow_builtin, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error) {
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec)) return read_frame_folder(input, anim, error);
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

}  // namespace dcurve
