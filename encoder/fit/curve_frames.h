// Cutting one curve's samples out of an animation, for fit_curve.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/fit/fit.h"
#include "encoder/io/frames.h"

namespace dcurve {

// The points of curve `curve` (vertex order and u from `curves`) at the animation frames
// `frames`, with segment time tau[k] for frames[k]. The caller guarantees valid ids.
CurveFrames gather_curve_frames(const Animation& anim, const Curves& curves, uint32_t curve,
                                const std::vector<uint32_t>& frames, const std::vector<double>& tau);

// Checks that `curves` partitions-or-covers vertex ids of `anim` consistently: offsets
// increasing from 0 to vertices.size(), ids < vertex_count, u parallel to vertices and in [0, 1].
bool validate_curves_for(const Animation& anim, const Curves& curves, std::string* error);

}  // namespace dcurve
