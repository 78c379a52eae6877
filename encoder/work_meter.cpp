#include "encoder/work_meter.h"

#include <algorithm>
#include <numeric>

namespace dcurve {

void WorkMeter::forecast(const std::vector<uint64_t>& stages) {
  std::lock_guard<std::mutex> lock(mu_);
  stages_ = stages;
  report_locked();
}

void WorkMeter::add(uint64_t frames) {
  std::lock_guard<std::mutex> lock(mu_);
  in_stage_ += frames;
  planned_ += frames;
  report_locked();
}

void WorkMeter::end_stage() {
  std::lock_guard<std::mutex> lock(mu_);
  if (!stages_.empty()) {
    ended_ += stages_.front();
    stages_.erase(stages_.begin());
  }
  in_stage_ = 0;
  report_locked();
}

uint64_t WorkMeter::frames_planned() const {
  std::lock_guard<std::mutex> lock(mu_);
  return planned_;
}

// A stage that plans more than its forecast holds the bar at the stage's end until it ends.
void WorkMeter::report_locked() {
  if (!report_) return;
  const uint64_t ahead = std::accumulate(stages_.begin(), stages_.end(), uint64_t(0));
  const uint64_t total = ended_ + ahead;
  if (total == 0) return;
  const uint64_t current = stages_.empty() ? 0 : std::min(in_stage_, stages_.front());
  shown_ = std::max(shown_, double(ended_ + current) / double(total));
  report_(shown_);
}

}  // namespace dcurve
