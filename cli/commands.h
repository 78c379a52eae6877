// One function per `dcurve` subcommand; each registers its options on the app and returns
// the action to run after parsing. Actions return the process exit code:
// 0 success, 1 bad input or failure (a message naming the file and the problem on stderr).
#pragma once
#include <CLI/CLI.hpp>
#include <functional>

namespace dcurve::cli {

using Action = std::function<int()>;

Action add_simulate(CLI::App& app);
Action add_encode(CLI::App& app);
Action add_decode(CLI::App& app);
Action add_info(CLI::App& app);
Action add_bench(CLI::App& app);

}  // namespace dcurve::cli
