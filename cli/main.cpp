// dcurve: compression codec for animated triangle meshes. Exit codes: 0 success,
// 1 bad input or failure, 2 bad usage.
#include <cstdio>
#include <exception>

#include "cli/commands.h"
#include "encoder/io/signal_cleanup.h"

int main(int argc, char** argv) {
  CLI::App app{"dcurve: compress animated triangle meshes into dynamic PDE curves (.dcrv)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "dcurve 0.1.0");
  std::vector<std::pair<CLI::App*, dcurve::cli::Action>> commands;
  auto reg = [&](const char* name, const char* help, dcurve::cli::Action (*add)(CLI::App&)) {
    CLI::App* sub = app.add_subcommand(name, help);
    commands.emplace_back(sub, add(*sub));
  };
  reg("simulate", "Simulate a scene with XPBD on a TetGen tet mesh and write its frames", dcurve::cli::add_simulate);
  reg("encode", "Encode frames (a folder, glTF, PC2/MDD or a scene) into a .dcrv file within a max error", dcurve::cli::add_encode);
  reg("decode", "Evaluate a .dcrv file at frames or any time t: meshes, glTF, PC2/MDD", dcurve::cli::add_decode);
  reg("info", "Describe what is inside a .dcrv file", dcurve::cli::add_info);
  reg("bench", "Compare size, error and speed with Draco and the other baselines", dcurve::cli::add_bench);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  dcurve::remove_temporary_on_signal();
  try {
    for (auto& [sub, action] : commands)
      if (sub->parsed()) return action();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "dcurve: %s\n", e.what());
    return 1;
  }
  return 2;
}
