// What a subcommand says: errors always (stderr, "dcurve <command>: " first), the summary
// line unless -q, details with -v (stderr, prefixed), progress unless -q (cli/progress.h).
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <string>

namespace dcurve::cli {

class Messages {
 public:
  explicit Messages(std::string command) : command_(std::move(command)) {}
  // Registers -q/--quiet and -v/--verbose on the subcommand.
  void add_flags(CLI::App& app);
  bool quiet() const { return quiet_; }
  // Prints the error and returns 1, the exit code of bad input or failure.
  int error(const std::string& message) const;
  void detail(const std::string& message) const;
  // What the user should know though nothing failed (input the command does not keep); unless -q.
  void note(const std::string& message) const;
  // The progress callback for the stage `label` (empty when quiet).
  std::function<void(double)> progress(const std::string& label) const;

 private:
  std::string command_;
  bool quiet_ = false, verbose_ = false;
};

}  // namespace dcurve::cli
