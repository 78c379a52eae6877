// Running the dcurve CLI from a test (only the tests built with the CLI define DCURVE_CLI).
#pragma once
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace dcurve::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// The dcurve CLI under test: the one built beside the tests, or the program DCURVE_TEST_CLI
// names (to run the tests against another build, e.g. main's).
inline std::string cli_program() {
  const char* other = std::getenv("DCURVE_TEST_CLI");
  return other && *other ? other : DCURVE_CLI;
}

// Runs the shell command `command` (stdout and stderr captured). stderr is a pipe here, where
// the CLI prints a progress line every few seconds (cli/progress.h): every `progress_seconds`,
// by default so rarely that the output holds only what the command says.
inline CommandResult run_cli_command(const std::string& command, double progress_seconds = 1e6) {
  CommandResult r;
  const std::string cmd =
      "(export DCURVE_PROGRESS_INTERVAL=" + std::to_string(progress_seconds) + "; " + command + ") 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.output.append(buf.data(), n);
  int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Runs `args` with the dcurve CLI through the shell.
inline CommandResult run_cli(const std::string& args, double progress_seconds = 1e6) {
  return run_cli_command(cli_program() + " " + args, progress_seconds);
}

}  // namespace dcurve::test
