// What the residual rate control chose, read back from a decoded Model: how often each
// predictor kind and spatial correction serves a (frame, axis), and the coding order.
// `dcurve info` and `dcurve bench` print it.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "codec/model.h"

namespace dcurve {

// {"kind": {name: count}, "spatial": {name: count}, "coding_order": "time"|"hierarchical"},
// or null when the model has no residual layer or its plan cannot be decoded.
nlohmann::json predictor_use(const Model& model);

// One line for tables, e.g. "reference 90, linear 45; blend 120, mean 15; hierarchical order";
// empty when predictor_use is null.
std::string predictor_use_text(const nlohmann::json& use);

}  // namespace dcurve
