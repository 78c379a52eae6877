// `dcurve bench --inbetween`: how well a file fills the time between its frames. The even
// frames of an input are encoded, the file is decoded at the odd frames' times, and the
// RMSE against the true odd frames is reported for each in-between rule and for the rule the
// file records, beside the same rules through the TRUE even frames (no coding error: what a
// free cubic gives). Optionally the same with a PDE motion model kept in the file.
#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/encoder.h"
#include "encoder/io/frames.h"

namespace dcurve::bench {

struct InbetweenFile {
  bool present = false;
  uint64_t bytes = 0;
  Inbetween recorded = Inbetween::Linear;
  double rmse[kInbetweenCount] = {0, 0, 0};  // the file decoded with each rule forced
  double rmse_recorded = 0;                   // with the rule it records
  double rmse_stored = 0;                     // at the stored (even) frames
  std::string settings;                       // the model kept (PDE file)
};

struct InbetweenResult {
  std::string input;
  uint32_t vertices = 0, frames = 0, held_out = 0;
  InbetweenFile plain;  // the default encode of the even frames
  InbetweenFile pde;    // with --model pde --keep-all-motions, when asked for
  double true_rmse[kInbetweenCount] = {0, 0, 0};  // each rule through the true even frames
};

// Encodes the even frames of `anim` with `options` (and, with `with_pde`, again with a PDE
// model whose motions are all kept) and measures the in-betweens at the odd frames. RMSE in
// fractions of the rest-pose diagonal L. False with *error when an encode fails or the
// input has fewer than 3 frames.
bool run_inbetween_bench(const std::string& name, const Animation& anim, const EncodeOptions& options,
                         bool with_pde, InbetweenResult* result, std::string* error);

std::string inbetween_table(const std::vector<InbetweenResult>& results);
nlohmann::json inbetween_json(const std::vector<InbetweenResult>& results);

}  // namespace dcurve::bench
