// What `encode` and `bench` accept as an animation: a folder of frames, a scene file (the
// simulation runs inline) or the name of a built-in scene.
#pragma once
#include <functional>
#include <string>

#include "encoder/io/frames.h"

namespace dcurve {

// Loads `input`: a folder -> read_frame_folder; an existing file -> load_scene_file then
// simulate_scene; otherwise a built-in scene name when `allow_builtin`. Errors name the input.
bool load_animation_input(const std::string& input, bool allow_builtin, const std::function<void(double)>& progress,
                          Animation* anim, std::string* error);

}  // namespace dcurve
