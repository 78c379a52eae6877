// The in-between rules of format_spec/dcrv.md section 13: the weights with which frames
// i - 2 .. i + 3 of a segment enter the output between frames i and i + 1. Decoder,
// encoder (which chooses the rule) and benchmarks share this one definition.
#pragma once
#include <cstdint>

#include "codec/common/model.h"

namespace dcurve {

// Frames i - 2 .. i + 3: weight[k] belongs to frame i - 2 + k.
constexpr int kInbetweenStencil = 6;
constexpr int kInbetweenStencilFirst = -2;

// Weights of the stencil frames for the position at i + w (0 <= w <= 1) in a segment of
// frames [first, last] with first <= i < last: frames outside [first, last] get weight 0,
// the weights sum to 1, w = 0 gives frame i alone and w = 1 frame i + 1 alone.
void inbetween_weights(Inbetween rule, uint32_t first, uint32_t last, uint32_t i, double w,
                       double weight[kInbetweenStencil]);

// The rule's name as the command line spells it ("linear", "catmull-rom", "hermite4"), and
// back; false for an unknown name.
const char* inbetween_name(Inbetween rule);
bool inbetween_from_name(const char* name, Inbetween* rule);

}  // namespace dcurve
