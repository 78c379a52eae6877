// An encode's progress counted in frame plans: one frame's predictors and grid values chosen
// once, by a coding order's planner or a cluster layout's. Nearly all of an encode's time goes
// to them, so frames planned against a forecast of how many the encode will plan give a
// fraction done, and a time left, that a user can trust.
#pragma once
#include <cstdint>
#include <functional>
#include <mutex>
#include <vector>

namespace dcurve {

class WorkMeter {
 public:
  // report: receives the fraction done, in [0, 1] and never decreasing; may be empty.
  explicit WorkMeter(std::function<void(double)> report) : report_(std::move(report)) {}

  // The forecast frame plans of each stage still to run, in order (replaces any earlier
  // forecast of stages not yet ended).
  void forecast(const std::vector<uint64_t>& stages);
  // `frames` more frames planned in the current stage. Thread-safe.
  void add(uint64_t frames);
  // Ends the current stage: whatever its forecast did not use counts as done, so a forecast
  // that was too high shows as a step rather than as a bar that stops short.
  void end_stage();
  // Frames planned in every stage so far.
  uint64_t frames_planned() const;

 private:
  void report_locked();

  std::function<void(double)> report_;
  mutable std::mutex mu_;
  std::vector<uint64_t> stages_;  // forecasts; stages_[0] is the current stage's
  uint64_t ended_ = 0;            // the forecasts of the stages that ended
  uint64_t in_stage_ = 0;         // frames planned in the current stage
  uint64_t planned_ = 0;          // frames planned in all stages
  double shown_ = 0;
};

}  // namespace dcurve
