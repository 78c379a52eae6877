#include "codec/compress/quantize.h"

#include <algorithm>
#include <cmath>

namespace dcurve {
namespace {
using container_format::u_from_fixed;
using container_format::u_to_fixed;
}  // namespace

float quantize_curve_u(float u) { return u_from_fixed(u_to_fixed(u)); }

int quantize_coefficients(CurveMotion* m, int exponent) {
  double largest = 0;
  for (float c : m->coeffs) largest = std::max(largest, std::fabs(double(c)));
  // |k| = |c| / 2^e rounds to at most 2^24 - 1 when 2^e >= |c| / (2^24 - 1).
  if (largest > 0 && std::isfinite(largest))
    exponent = std::max(exponent, int(std::ceil(std::log2(largest / double((1 << kCoeffIntegerBits) - 1)))));
  exponent = std::min(std::max(exponent, kCoeffExponentMin), kCoeffExponentMax);
  m->coeff_exponent = int8_t(exponent);
  for (float& c : m->coeffs)
    c = std::ldexp(float(std::round(std::ldexp(double(c), -exponent))), exponent);
  return exponent;
}

}  // namespace dcurve
