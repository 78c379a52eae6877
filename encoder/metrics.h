// The error measures of DESIGN.md section 5, used by encode, bench and the tests.
#pragma once
#include <vector>

#include "encoder/io/frames.h"

namespace dcurve {

// L: bounding-box diagonal of a frame (xyz, 3 floats per vertex), model units.
double bbox_diagonal(const std::vector<float>& xyz);

struct ErrorStats {
  double max_error = 0;     // max over frames and vertices of |x^ - x| / L
  double rmse = 0;          // sqrt(mean over frames and vertices of |x^ - x|^2) / L
  double kg_error_pct = 0;  // Karni-Gotsman: 100 |A - A^|_F / |A - E(A)|_F, E(A) = per-frame centroid
  std::vector<double> max_error_per_frame;  // fraction of L
};

// Compares `decoded` with `reference` frame by frame; L is the reference's frame-0 diagonal.
ErrorStats measure_error(const Animation& reference, const std::vector<std::vector<float>>& decoded);

}  // namespace dcurve
