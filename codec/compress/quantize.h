// Quantizing what the container stores with less precision than the encoder computes, so
// the encoder's closed loop sees exactly what a reader gets back.
#pragma once
#include "codec/common/container_format.h"
#include "codec/common/model.h"

namespace dcurve {

// The value a reader gets back for curve parameter u (stored as 16-bit fixed point): an
// encoder fits against these so its closed loop sees what the decoder sees. u in [0, 1].
float quantize_curve_u(float u);

// Rounds every coefficient of `m` to the nearest multiple of 2^exponent (to nearest, ties
// away from zero) and stores the exponent, which is first raised as far as the largest
// coefficient needs for |k| < 2^24 and clamped to [kCoeffExponentMin, kCoeffExponentMax].
// The result is exactly what a reader gets back. Returns the exponent used.
int quantize_coefficients(CurveMotion* m, int exponent);

}  // namespace dcurve
