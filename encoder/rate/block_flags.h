// The encoder's last step on the residual layer: the chosen payloads (the LRNK basis and
// RESI) recoded with block flags (format 3.1, payload version 4: a block of 16 zero
// residuals costs the decoder its predictions only), each kept when it codes smaller. The
// search before it measures without the flags, so its choices are those of format 3.0.
#pragma once
#include <string>

#include "codec/common/model.h"
#include "encoder/rate/coded_residual.h"

namespace dcurve {

enum class BlockFlagUse { WhenSmaller, Always };

// Recodes *model's residual payloads with block flags: the same plans and values, other
// bytes. `coded` (may be null) is what the payloads code, as the encoder left them; without
// it the payloads are decoded for their plans and values. Fails only on a payload that does
// not decode (an internal error).
bool use_block_flags(Model* model, BlockFlagUse when, std::string* error, const CodedResidual* coded = nullptr);

}  // namespace dcurve
