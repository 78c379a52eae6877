// u along a curve (ParamRule) and the edits that need u recomputed (split_curve).
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "encoder/curves/extract.h"

namespace dcurve {
namespace {

// Length of the step a -> b under `rule`: Euclidean for chord length, |dw| on `axis` for the
// coordinate-range rule.
double step_length(const std::vector<float>& xyz, uint32_t a, uint32_t b, ParamRule rule, int axis) {
  if (rule == ParamRule::CoordinateRange) return std::fabs(double(xyz[3 * b + axis]) - xyz[3 * a + axis]);
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double d = double(xyz[3 * b + k]) - xyz[3 * a + k];
    s += d * d;
  }
  return std::sqrt(s);
}

// The axis along which the curve's points spread most (eq. (10) is applied on it).
int widest_axis(const std::vector<float>& xyz, const uint32_t* v, uint32_t n) {
  int best = 0;
  double best_range = -1.0;
  for (int axis = 0; axis < 3; ++axis) {
    float lo = xyz[3 * v[0] + axis], hi = lo;
    for (uint32_t i = 1; i < n; ++i) {
      lo = std::min(lo, xyz[3 * v[i] + axis]);
      hi = std::max(hi, xyz[3 * v[i] + axis]);
    }
    if (double(hi) - lo > best_range) {
      best_range = double(hi) - lo;
      best = axis;
    }
  }
  return best;
}

}  // namespace

void parameterize_curve(Curves* curves, uint32_t curve, const std::vector<float>& rest_xyz, ParamRule rule) {
  if (curve >= curves->curve_count()) throw std::invalid_argument("parameterize_curve: curve index out of range");
  const uint32_t begin = curves->offsets[curve], n = curves->offsets[curve + 1] - begin;
  const uint32_t* v = curves->vertices.data() + begin;
  float* u = curves->u.data() + begin;
  if (curves->u.size() != curves->vertices.size()) throw std::invalid_argument("parameterize_curve: u size differs from vertices");
  if (n == 0) return;
  const bool closed = curves->closed[curve] != 0 && n >= 3;
  const int axis = rule == ParamRule::CoordinateRange ? widest_axis(rest_xyz, v, n) : 0;
  std::vector<double> s(n, 0.0);
  for (uint32_t i = 1; i < n; ++i) s[i] = s[i - 1] + step_length(rest_xyz, v[i - 1], v[i], rule, axis);
  const double total = s[n - 1] + (closed ? step_length(rest_xyz, v[n - 1], v[0], rule, axis) : 0.0);
  // Coincident points (or a curve flat along the chosen axis) fall back to even spacing.
  const uint32_t steps = closed ? n : n - 1;
  for (uint32_t i = 0; i < n; ++i) {
    const double t = total > 0.0 ? s[i] / total : (steps > 0 ? double(i) / steps : 0.0);
    u[i] = std::min(1.f, float(t));
  }
  if (!closed && n >= 2) u[n - 1] = 1.f;
}

void split_curve(Curves* curves, uint32_t curve, uint32_t at, const std::vector<float>& rest_xyz, ParamRule rule) {
  if (curve >= curves->curve_count()) throw std::invalid_argument("split_curve: curve index out of range");
  const uint32_t begin = curves->offsets[curve], n = curves->offsets[curve + 1] - begin;
  if (at < 1 || at >= n) throw std::invalid_argument("split_curve: split point must satisfy 1 <= at < curve size");
  if (curves->closed[curve]) {
    std::rotate(curves->vertices.begin() + begin, curves->vertices.begin() + begin + at,
                curves->vertices.begin() + begin + n);
    curves->closed[curve] = 0;
    parameterize_curve(curves, curve, rest_xyz, rule);
    return;
  }
  curves->offsets.insert(curves->offsets.begin() + curve + 1, begin + at);
  curves->closed.insert(curves->closed.begin() + curve + 1, uint8_t(0));
  parameterize_curve(curves, curve, rest_xyz, rule);
  parameterize_curve(curves, curve + 1, rest_xyz, rule);
}

}  // namespace dcurve
