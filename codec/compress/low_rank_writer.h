// Writing the LRNK section's payload (codec/common/low_rank.h describes the model;
// codec/decompress/low_rank_reader.h reads it back).
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// Raw LRNK payload of model.low_rank (components > 0, coeffs sized frame_count * K).
std::vector<uint8_t> low_rank_bytes(const Model& model);

}  // namespace dcurve
