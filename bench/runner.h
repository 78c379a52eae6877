// `dcurve bench`: dcurve and every baseline on the same frames at the same max error, in one
// run, so the ratios compare like with like. Errors come from decoding each method's bytes.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "encoder/encoder.h"
#include "encoder/io/frames.h"

namespace dcurve::bench {

struct MethodResult {
  std::string method;             // "dcurve", "draco_per_frame", "draco_keyframes", "pca", ...
  uint64_t bytes = 0;             // everything a decoder needs, connectivity included
  uint64_t connectivity_bytes = 0;  // the connectivity share of `bytes`
  double bpvf = 0;                // 8 * bytes / (vertices * frames)
  double max_error = 0, rmse = 0;  // fractions of the rest-pose diagonal L (DESIGN.md sec. 5)
  double kg_error_pct = 0;        // Karni-Gotsman error, percent
  double encode_seconds = 0;      // wall time of the encode, parameter search included
  double decode_vertices_per_second = 0;  // vertices * frames / seconds to decode every frame
  bool meets_tolerance = false;   // max_error <= tolerance and the method ran
  std::string settings;           // chosen parameters, or why the method failed
};

struct InputResult {
  std::string input;
  double tolerance;
  uint32_t vertices, frames;
  std::vector<MethodResult> methods;
};

// Every method name run_bench knows, in the order it runs them.
const std::vector<std::string>& all_methods();

// Runs `methods` (names from all_methods(); empty = all) on `anim` at max error `tolerance`
// (fraction of the rest-pose diagonal, in (0, 0.5]). `progress` (may be empty) gets the
// fraction done in [0, 1]; `dcurve_effort` (EncodeOptions::effort, in [kMinEffort,
// kMaxEffort]) is how widely the dcurve method's encoder searches. Throws
// std::invalid_argument on an invalid animation, tolerance, method name or effort; a method
// that fails is reported with meets_tolerance = false.
InputResult run_bench(const std::string& name, const Animation& anim, double tolerance,
                      const std::vector<std::string>& methods, const std::function<void(double)>& progress,
                      int dcurve_effort = EncodeOptions().effort);

// All methods.
InputResult run_bench(const std::string& name, const Animation& anim, double tolerance,
                      const std::function<void(double)>& progress);

// The human table printed by `dcurve bench`: one block per input and tolerance.
std::string format_table(const std::vector<InputResult>& results);

}  // namespace dcurve::bench
