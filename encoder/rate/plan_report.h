// What the residual rate control chose, read back from a decoded Model: how often each
// predictor kind and spatial correction serves a (frame, axis), and the coding order.
// `dcurve info` and `dcurve bench` print it.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "codec/common/model.h"

namespace dcurve {

// {"kind", "spatial": {name: count} of each frame's first candidate per axis; "coding_order":
// "time"|"hierarchical"; "cluster_size", "clusters", "candidates", "clustered_frames";
// "cluster_kind": {name: count} over every (frame, cluster, axis); "motion_transforms"},
// or null when the model has no residual layer or its plan cannot be decoded.
nlohmann::json predictor_use(const Model& model);

// One line for tables, e.g. "reference 90, linear 45; blend 120, mean 15; hierarchical order";
// empty when predictor_use is null.
std::string predictor_use_text(const nlohmann::json& use);

}  // namespace dcurve
