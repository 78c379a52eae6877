// Reading the LRNK section's payload (codec/common/low_rank.h describes the model), as
// codec/compress/low_rank_writer.h wrote it.
#pragma once
#include "codec/common/bytes.h"
#include "codec/common/model.h"

namespace dcurve {

// Parses an LRNK payload into model->low_rank; model->meta must already hold frame_count.
// fast_format: the file is of major 4, where packed differences are allowed. False on any
// field out of range or a count the remaining bytes cannot hold.
bool parse_low_rank(ByteReader& r, Model* model, bool fast_format);

}  // namespace dcurve
