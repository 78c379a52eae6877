#include <cstdio>

#include "cli/commands.h"

namespace dcurve::cli {

Action add_simulate(CLI::App& app) {
  struct Opts {
    std::string scene_file, scene_name, output;
    bool list = false;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("scene", o->scene_file, "Scene file (.json)");
  app.add_option("--scene", o->scene_name, "Built-in scene name");
  app.add_option("-o,--output", o->output, "Output folder for frame_00000.obj, ...");
  app.add_flag("--list", o->list, "List the built-in scenes");
  return [o]() {
    std::fprintf(stderr, "dcurve simulate: the XPBD simulator is not built yet\n");
    return 1;
  };
}

}  // namespace dcurve::cli
