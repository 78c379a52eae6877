#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/frame_output.h"
#include "cli/messages.h"
#include "cli/output_path.h"
#include "corpus/sim/scene.h"
#include "encoder/io/output_folder.h"

namespace dcurve::cli {
namespace {

// The files a simulation reads: never its output.
std::vector<std::string> scene_inputs(const std::string& scene_file, const Scene& scene) {
  std::vector<std::string> files;
  if (!scene_file.empty()) files.push_back(scene_file);
  if (!scene.mesh_file.empty()) files.push_back(scene.mesh_file);
  return files;
}

// Streams the simulated frames into the output (cli/frame_output).
bool write_frames(const std::string& path, OutputKind kind, bool force, const Animation& anim,
                  const std::vector<std::string>& inputs, std::string* error) {
  OutputSpec spec;
  spec.path = path;
  spec.kind = kind;
  spec.force = force;
  spec.vertex_count = anim.vertex_count;
  spec.frame_count = uint32_t(anim.frames.size());
  spec.faces = anim.faces;
  spec.frame_rate = anim.frame_rate;
  spec.inputs = inputs;
  auto sink = open_output(spec, error);
  if (!sink) return false;
  for (size_t f = 0; f < anim.frames.size(); ++f)
    if (!sink->add(uint32_t(f), anim.frames[f].data(), nullptr, error)) return false;
  return sink->finish(error);
}

// The kinds simulate writes: those of decode but one mesh.
std::vector<OutputKind> simulate_kinds() {
  return {OutputKind::Folder, OutputKind::Gltf, OutputKind::PointCache};
}

}  // namespace

Action add_simulate(CLI::App& app) {
  struct Opts {
    std::string scene_file, scene_name, output;
    bool list = false, force = false;
    int frames = 0;
  };
  auto o = std::make_shared<Opts>();
  auto msg = std::make_shared<Messages>("simulate");
  auto* file = app.add_option("scene", o->scene_file, "Scene file (.json)");
  auto* name = app.add_option("--scene", o->scene_name, "Built-in scene name (see --list)");
  file->excludes(name);
  name->excludes(file);
  app.add_option("-o,--output", o->output,
                 "Output: a folder for frame_00000.obj, ... (a name ending in / or without extension), a glTF "
                 "file (.glb/.gltf) or a point cache (.pc2/.mdd)");
  app.add_flag("--force", o->force, "Replace an existing output file, or the frames of an output folder");
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
    OutputKind kind;
    if (!output_kind(o->output, simulate_kinds(), &kind, &err)) return msg->error(err);
    const bool ok = o->scene_file.empty() ? builtin_scene(o->scene_name, &scene, &err)
                                          : load_scene_file(o->scene_file, &scene, &err);
    if (!ok) return msg->error(err);
    if (o->frames > 0) scene.frames = o->frames;
    const std::vector<std::string> inputs = scene_inputs(o->scene_file, scene);
    const bool writable = kind == OutputKind::Folder ? OutputFolder::check(o->output, o->force, &err)
                                                     : check_output_file(o->output, o->force, inputs, &err);
    if (!writable) return msg->error(err);
    Animation anim;
    if (!simulate_scene(scene, &anim, msg->progress("simulate"), &err)) return msg->error(err);
    if (!write_frames(o->output, kind, o->force, anim, inputs, &err)) return msg->error(err);
    msg->detail("wrote " + std::to_string(anim.frames.size()) + " frames of " + std::to_string(anim.vertex_count) +
                " vertices to " + o->output);
    return 0;
  };
}

}  // namespace dcurve::cli
