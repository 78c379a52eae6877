#include "cli/progress.h"

#include <unistd.h>

#include <cstdio>
#include <memory>
#include <mutex>

namespace dcurve::cli {

std::function<void(double)> progress_bar(const std::string& label) {
  if (!isatty(STDERR_FILENO) || !isatty(STDOUT_FILENO)) return {};
  struct State {
    std::mutex mu;
    int shown = -1;
  };
  auto state = std::make_shared<State>();
  return [label, state](double fraction) {
    std::lock_guard<std::mutex> lock(state->mu);
    int pct = int(fraction * 100.0 + 0.5);
    pct = pct < 0 ? 0 : pct > 100 ? 100 : pct;
    if (pct == state->shown) return;
    state->shown = pct;
    const int width = 30;
    int filled = pct * width / 100;
    std::fprintf(stderr, "\r%-12s [%.*s%*s] %3d%%", label.c_str(), filled, "##############################",
                 width - filled, "", pct);
    if (pct == 100) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace dcurve::cli
