#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/messages.h"
#include "corpus/sim/scene.h"
#include "encoder/io/frames.h"

namespace dcurve::cli {

Action add_simulate(CLI::App& app) {
  struct Opts {
    std::string scene_file, scene_name, output;
    bool list = false;
    int frames = 0;
  };
  auto o = std::make_shared<Opts>();
  auto msg = std::make_shared<Messages>("simulate");
  auto* file = app.add_option("scene", o->scene_file, "Scene file (.json)");
  auto* name = app.add_option("--scene", o->scene_name, "Built-in scene name (see --list)");
  file->excludes(name);
  name->excludes(file);
  app.add_option("-o,--output", o->output, "Output folder for frame_00000.obj, ...");
  app.add_option("--frames", o->frames, "Override the scene's frame count (>= 1)")->check(CLI::PositiveNumber);
  app.add_flag("--list", o->list, "List the built-in scenes and exit");
  msg->add_flags(app);
  return [o, msg]() {
    if (o->list) {
      for (const auto& n : builtin_scene_names()) std::printf("%s\n", n.c_str());
      return 0;
    }
    if (o->scene_file.empty() == o->scene_name.empty() || o->output.empty()) {
      std::fprintf(stderr, "dcurve simulate: give one of SCENE.json or --scene NAME, and -o DIR\n");
      return 2;
    }
    Scene scene;
    std::string err;
    const bool ok = o->scene_file.empty() ? builtin_scene(o->scene_name, &scene, &err)
                                          : load_scene_file(o->scene_file, &scene, &err);
    if (!ok) return msg->error(err);
    if (o->frames > 0) scene.frames = o->frames;
    Animation anim;
    if (!simulate_scene(scene, &anim, msg->progress("simulate"), &err)) return msg->error(err);
    if (!write_frame_folder(o->output, anim, "obj", &err)) return msg->error(err);
    msg->detail("wrote " + std::to_string(anim.frames.size()) + " frames of " + std::to_string(anim.vertex_count) +
                " vertices to " + o->output);
    return 0;
  };
}

}  // namespace dcurve::cli
