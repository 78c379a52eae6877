// The low-rank model of a fast-profile file (format 4). Format 3's choice (low_rank_choice.h)
// judges a model by what it saves that coder, whose spatial predictors leave a low-rank model
// little to do (one component on horse-gallop); the fast coder's one predictor per frame leans
// on the model, so its count is chosen by the fast file's own bytes.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "encoder/rate/fast_plan.h"

namespace dcurve {

// m: a model without PDE motions (its grid, faces, curves). rounded: the input's nearest
// grid values (frame-major). Tries component counts (options.components) at a fixed basis
// step, each with a fast residual layer, then coarser steps for the best, and leaves in *m
// the smallest whole file's low-rank model and fast payload (none, if no model pays).
// bytes (may be null): that file's size, faces in the layout write_container picks.
bool choose_fast_low_rank(Model* m, const std::vector<std::vector<float>>& frames, const std::vector<int32_t>& rounded,
                          const FastLayerOptions& options, std::string* error, size_t* bytes = nullptr);

// Recodes m's low-rank mean and basis (if any) as a fast payload, each pseudo-frame from
// itself alone through the fast traversal, so a decoder opens the file without format 3's
// spatial weight tables. The values are unchanged: `values` (may be null), those its basis
// payload codes, as the encoder kept them; else decoded from the payload.
bool fast_low_rank_basis(Model* m, std::string* error, const std::vector<int32_t>* values = nullptr);

}  // namespace dcurve
