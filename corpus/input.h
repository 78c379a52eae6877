// What `encode` and `bench` accept as an animation: a folder of frames, a scene file (the
// simulation runs inline) or the name of a built-in scene.
#pragma once
#include <functional>
#include <string>

#include "encoder/io/frames.h"
#include "encoder/io/read_limits.h"

namespace dcurve {

// Loads `input`: a folder -> read_frame_folder; an existing file -> load_scene_file then
// simulate_scene; otherwise a built-in scene name when `allow_builtin`. Errors name the input.
bool load_animation_input(const std::string& input, bool allow_builtin, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error);

// What only some inputs need. `fps` > 0 overrides the frame rate the input has (folders
// have none: 30 unless given).
struct InputOptions {
  std::string rest_mesh;  // the faces of a point cache (.pc2, .mdd), whose vertex count must match
  int gltf_mesh = -1;     // which mesh of a glTF file (-1: the file must hold one)
  double fps = 0;
  ReadLimits limits;      // memory and glTF resource folders (glTF and point caches)
};

// "simulate" when `input` names a scene (a file that is not a glTF, a point cache or a mesh
// folder, or a built-in scene's name), "read" otherwise: the progress label of loading it.
std::string input_stage_label(const std::string& input);

// As above, and also a glTF file (.gltf, .glb) or a point cache with its rest mesh.
bool load_animation_input(const std::string& input, const InputOptions& options, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error);

}  // namespace dcurve
