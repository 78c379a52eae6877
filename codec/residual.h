// The residual layer: integer grid positions of every input frame, coded against
// predictions. Encoder and decoder share this file so the round trip is exact.
//
// Grid positions are laid out frame-major: q[(f * V + v) * 3 + axis].
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

// Codes the grid positions `q` (frame_count * vertex_count * 3 values) of `model` into a
// payload for model.residual.payload. `model` supplies counts and curves.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q);

// Reverses encode_residuals. `q` receives frame_count * vertex_count * 3 values. Returns
// false with a message on a malformed payload; never reads outside the payload.
bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error);

}  // namespace dcurve
