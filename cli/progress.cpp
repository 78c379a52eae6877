#include "cli/progress.h"

#include <unistd.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <thread>

namespace dcurve::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

int percent_of(double fraction) {
  const int pct = int(fraction * 100.0 + 0.5);
  return pct < 0 ? 0 : pct > 100 ? 100 : pct;
}

// ", about 42 s left" at the pace so far; empty until some work is done, and when finished.
std::string time_left(int pct, double elapsed) {
  if (pct <= 0 || pct >= 100) return "";
  char text[48];
  std::snprintf(text, sizeof text, ", about %.0f s left", elapsed * (100 - pct) / pct);
  return text;
}

// The redrawn bar of a terminal.
class Bar {
 public:
  explicit Bar(std::string label) : label_(std::move(label)) {}
  void update(double fraction) {
    std::lock_guard<std::mutex> lock(mu_);
    const int pct = percent_of(fraction);
    if (pct == shown_) return;
    shown_ = pct;
    const int width = 30, filled = pct * width / 100;
    std::fprintf(stderr, "\r%-12s [%.*s%*s] %3d%%%-24s", label_.c_str(), filled, "##############################",
                 width - filled, "", pct, time_left(pct, seconds_since(start_)).c_str());
    if (pct == 100) std::fputc('\n', stderr);
    std::fflush(stderr);
  }

 private:
  std::string label_;
  std::mutex mu_;
  int shown_ = -1;
  Clock::time_point start_ = Clock::now();
};

double line_interval() {
  const char* env = std::getenv("DCURVE_PROGRESS_INTERVAL");
  const double s = env ? std::atof(env) : 0.0;
  return s > 0 ? s : kProgressLineSeconds;
}

// Periodic lines: a thread wakes every interval and prints the latest fraction, since the
// encoder reports progress only between its long steps.
class Lines {
 public:
  Lines(std::string label, std::string prefix)
      : label_(std::move(label)), prefix_(std::move(prefix)), ticker_(&Lines::tick, this) {}
  ~Lines() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      done_ = true;
    }
    wake_.notify_all();
    ticker_.join();
  }
  void update(double fraction) {
    std::lock_guard<std::mutex> lock(mu_);
    if (done_) return;
    fraction_ = fraction;
    if (percent_of(fraction) < 100) return;
    done_ = true;
    if (printed_) print_line();  // a log that showed the stage shows its end too
    wake_.notify_all();
  }

 private:
  void tick() {
    std::unique_lock<std::mutex> lock(mu_);
    const auto interval = std::chrono::duration<double>(line_interval());
    while (!wake_.wait_for(lock, interval, [this] { return done_; })) print_line();
  }
  void print_line() {  // with mu_ held
    const int pct = percent_of(fraction_);
    const double elapsed = seconds_since(start_);
    std::fprintf(stderr, "%s%s %d%%, %.0f s%s\n", prefix_.c_str(), label_.c_str(), pct, elapsed,
                 time_left(pct, elapsed).c_str());
    std::fflush(stderr);
    printed_ = true;
  }

  std::string label_, prefix_;
  std::mutex mu_;
  std::condition_variable wake_;
  double fraction_ = 0;
  bool done_ = false, printed_ = false;
  Clock::time_point start_ = Clock::now();
  std::thread ticker_;  // last: starts once every other member is ready
};

}  // namespace

std::function<void(double)> progress_bar(const std::string& label, const std::string& prefix) {
  if (isatty(STDERR_FILENO)) {
    auto bar = std::make_shared<Bar>(label);
    return [bar](double fraction) { bar->update(fraction); };
  }
  auto lines = std::make_shared<Lines>(label, prefix);
  return [lines](double fraction) { lines->update(fraction); };
}

}  // namespace dcurve::cli
