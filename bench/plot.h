// The rate-distortion plot of `dcurve bench --plot`: for each input, bits per vertex per
// frame against measured max error, one line per method across the tolerances run.
#pragma once
#include <string>
#include <vector>

#include "bench/runner.h"

namespace dcurve::bench {

// A standalone SVG document: one panel per distinct input name (in first-seen order), both
// axes logarithmic. Lossless methods (max error 0) sit in a strip left of the log axis; a hollow
// marker means the method missed the tolerance.
std::string rate_distortion_svg(const std::vector<InputResult>& results);

}  // namespace dcurve::bench
