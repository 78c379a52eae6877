// Bench results as a table, JSON and CSV. Ratios are bytes / bytes of the reference; NaN
// when the reference is missing or missed the tolerance (a method that misses the tolerance
// is no reference for size).
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "bench/runner.h"

namespace dcurve::bench {

// m.bytes / bytes of draco_per_frame in `in`.
double ratio_to_draco_per_frame(const InputResult& in, const MethodResult& m);

// m.bytes / bytes of the smallest baseline in `in` other than m (dcurve is never a
// baseline); the name of that baseline in *best when given.
double ratio_to_best_other(const InputResult& in, const MethodResult& m, std::string* best = nullptr);

// {"results": [{"input", "tolerance", "vertices", "frames", "methods": [{...}]}]}; keys
// listed in the bench README.
nlohmann::json results_json(const std::vector<InputResult>& results);

// One row per input, tolerance and method, with a header row.
std::string results_csv(const std::vector<InputResult>& results);

}  // namespace dcurve::bench
