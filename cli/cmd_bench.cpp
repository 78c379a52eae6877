#include <cstdio>

#include "cli/commands.h"

namespace dcurve::cli {

Action add_bench(CLI::App& app) {
  struct Opts {
    std::vector<std::string> inputs;
    bool json = false;
  };
  auto o = std::make_shared<Opts>();
  app.add_option("inputs", o->inputs, "Frame folders, scene files or built-in scene names");
  app.add_flag("--json", o->json, "Print one JSON object on stdout");
  return [o]() {
    std::fprintf(stderr, "dcurve bench: the comparison benchmark is not built yet\n");
    return 1;
  };
}

}  // namespace dcurve::cli
