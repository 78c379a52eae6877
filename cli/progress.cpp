#include "cli/progress.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <mutex>

namespace dcurve::cli {

std::function<void(double)> progress_bar(const std::string& label) {
  if (!isatty(STDERR_FILENO) || !isatty(STDOUT_FILENO)) return {};
  struct State {
    std::mutex mu;
    int shown = -1;
    std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
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
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - state->start).count();
    // Time left if the rest goes at the pace so far; unknown until some work is done.
    char left[32] = "";
    if (pct > 0 && pct < 100) std::snprintf(left, sizeof left, ", about %.0f s left", elapsed * (100 - pct) / pct);
    std::fprintf(stderr, "\r%-12s [%.*s%*s] %3d%%%-24s", label.c_str(), filled, "##############################",
                 width - filled, "", pct, left);
    if (pct == 100) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace dcurve::cli
