#include "codec/common/inbetween.h"

#include <cstring>

namespace dcurve {
namespace {

// Adds scale * (the tangent at frame f, per frame step) to the stencil weights of base
// frame i. Inside the segment: central differences (second order for Catmull-Rom, fourth
// order for Hermite4 where f +- 2 are in the segment); at its ends one-sided second-order
// differences, and the chord when the segment has two frames.
void add_tangent(Inbetween rule, uint32_t first, uint32_t last, uint32_t i, uint32_t f, double scale,
                 double weight[kInbetweenStencil]) {
  auto add = [&](uint32_t frame, double c) { weight[int(frame) - int(i) - kInbetweenStencilFirst] += scale * c; };
  if (last - first == 1) {
    add(last, 1.0);
    add(first, -1.0);
  } else if (f == first) {
    add(f, -1.5);
    add(f + 1, 2.0);
    add(f + 2, -0.5);
  } else if (f == last) {
    add(f, 1.5);
    add(f - 1, -2.0);
    add(f - 2, 0.5);
  } else if (rule == Inbetween::Hermite4 && f >= first + 2 && f + 2 <= last) {
    add(f - 2, 1.0 / 12);
    add(f - 1, -8.0 / 12);
    add(f + 1, 8.0 / 12);
    add(f + 2, -1.0 / 12);
  } else {
    add(f - 1, -0.5);
    add(f + 1, 0.5);
  }
}

}  // namespace

void inbetween_weights(Inbetween rule, uint32_t first, uint32_t last, uint32_t i, double w,
                       double weight[kInbetweenStencil]) {
  for (int k = 0; k < kInbetweenStencil; ++k) weight[k] = 0.0;
  const int at = -kInbetweenStencilFirst;  // frame i
  if (rule == Inbetween::Linear || w == 0.0) {
    weight[at] = 1.0 - w;
    weight[at + 1] += w;
    return;
  }
  // Cubic Hermite basis on [i, i + 1].
  const double w2 = w * w, w3 = w2 * w;
  weight[at] += 2 * w3 - 3 * w2 + 1;
  weight[at + 1] += -2 * w3 + 3 * w2;
  add_tangent(rule, first, last, i, i, w3 - 2 * w2 + w, weight);
  add_tangent(rule, first, last, i, i + 1, w3 - w2, weight);
}

const char* inbetween_name(Inbetween rule) {
  switch (rule) {
    case Inbetween::CatmullRom: return "catmull-rom";
    case Inbetween::Hermite4: return "hermite4";
    default: return "linear";
  }
}

bool inbetween_from_name(const char* name, Inbetween* rule) {
  for (uint8_t k = 0; k < kInbetweenCount; ++k)
    if (std::strcmp(name, inbetween_name(Inbetween(k))) == 0) {
      *rule = Inbetween(k);
      return true;
    }
  return false;
}

}  // namespace dcurve
