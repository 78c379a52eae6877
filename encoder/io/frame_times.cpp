#include "encoder/io/frame_times.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "codec/common/error.h"

namespace dcurve {
namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

bool check_finite_increasing(const std::vector<double>& times, const std::string& what, std::string* error) {
  for (size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]))
      return fail(error, what + ": time " + std::to_string(i) + " is " + number(times[i]) + ", not a finite number");
    if (i > 0 && !(times[i] > times[i - 1]))
      return fail(error, what + " do not increase strictly (time " + std::to_string(i) + " is " + number(times[i]) +
                             " s after " + number(times[i - 1]) + " s)");
  }
  return true;
}

}  // namespace

bool frame_rate_from_times(const std::vector<double>& times, const std::string& what, double* fps, std::string* error) {
  if (times.empty()) return fail(error, what + ": none");
  if (!check_finite_increasing(times, what, error)) return false;
  if (times.size() < 2) return true;
  const double dt = (times.back() - times.front()) / double(times.size() - 1);
  const double rate = 1.0 / dt;
  if (!(rate >= kMinFrameRate && rate <= kMaxFrameRate))
    return fail(error, what + " are " + number(dt) + " s apart: " + number(rate) + " frames per second, outside [" +
                           number(kMinFrameRate) + ", " + number(kMaxFrameRate) + "]");
  constexpr double kFloatEpsilon = std::numeric_limits<float>::epsilon();
  for (size_t i = 0; i < times.size(); ++i) {
    const double expected = times.front() + dt * double(i);
    if (std::abs(times[i] - expected) > 0.01 * dt + 2 * kFloatEpsilon * std::abs(expected))
      return fail(error, what + " are not evenly spaced (time " + std::to_string(i) + " is " + number(times[i]) +
                             " s, " + number(expected) + " s expected); dcurve needs one per frame, evenly spaced");
  }
  *fps = rate;
  return true;
}

bool check_start_time(double start, double fps, size_t frame_count, const std::string& what, std::string* error) {
  if (!std::isfinite(start)) return fail(error, what + " is " + number(start) + ", not a finite number");
  std::vector<double> times(frame_count);
  for (size_t f = 0; f < frame_count; ++f) times[f] = double(float(start + double(f) / fps));
  double rate = fps;
  std::string why;
  if (!frame_rate_from_times(times, "its frame times", &rate, &why))
    return fail(error, what + " is " + number(start) + " s: " + why + " as 32-bit floats (outputs store them so)");
  return true;
}

}  // namespace dcurve
