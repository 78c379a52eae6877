// The invariants a decoder checks before it evaluates anything from a file.
#pragma once
#include <cstdint>
#include <string>

#include "codec/model.h"

namespace dcurve {

// Upper bound on vertex_count * frame_count * 3 decoded values per coded residual byte:
// keeps a tiny hostile file from asking for gigabytes. Adaptive coding of a static mesh
// reaches about 0.01 bit per value, far inside this.
constexpr uint64_t kMaxValuesPerPayloadByte = 4096;
constexpr uint64_t kMaxValuesFloor = uint64_t(1) << 22;

bool validate_model(const Model& model, std::string* error);

}  // namespace dcurve
