#include "cli/messages.h"

#include <cstdio>

#include "cli/progress.h"

namespace dcurve::cli {

void Messages::add_flags(CLI::App& app) {
  auto* q = app.add_flag("-q,--quiet", quiet_, "Print errors only");
  app.add_flag("-v,--verbose", verbose_, "Also print what was read and written")->excludes(q);
}

int Messages::error(const std::string& message) const {
  std::fprintf(stderr, "dcurve %s: %s\n", command_.c_str(), message.c_str());
  return 1;
}

void Messages::detail(const std::string& message) const {
  if (verbose_) std::fprintf(stderr, "dcurve %s: %s\n", command_.c_str(), message.c_str());
}

void Messages::note(const std::string& message) const {
  if (!quiet_) std::fprintf(stderr, "dcurve %s: note: %s\n", command_.c_str(), message.c_str());
}

std::function<void(double)> Messages::progress(const std::string& label) const {
  return quiet_ ? std::function<void(double)>() : progress_bar(label, "dcurve " + command_ + ": ");
}

}  // namespace dcurve::cli
