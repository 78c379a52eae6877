// The invariants a decoder checks before it evaluates anything from a file.
#pragma once
#include <cstdint>
#include <string>

#include "codec/common/model.h"

namespace dcurve {

// Upper bound on vertex_count * frame_count * 3 decoded values per coded residual byte:
// keeps a tiny hostile file from asking for gigabytes. The range coder's probabilities stop
// at 4095/4096, so a perfectly static mesh costs at least 0.00035 bit per value (about
// 22,700 values per byte): this bound stays above that.
constexpr uint64_t kMaxValuesPerPayloadByte = 32768;
constexpr uint64_t kMaxValuesFloor = uint64_t(1) << 22;

bool validate_model(const Model& model, std::string* error);

}  // namespace dcurve
