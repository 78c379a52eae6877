// The chunk length of the residual layer. A decoder decodes a whole chunk to reach any of
// its frames and holds one, so short chunks cost less memory and random-access time; they
// cost bytes (each chunk restarts the coder's statistics and codes its first frame without
// the frames before it). The encoder measures the final residual layer at each candidate
// length and keeps the shortest whose file is within kChunkSlack of the smallest.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/predictors.h"
#include "codec/compress/container_writer.h"
#include "encoder/rate/coded_residual.h"
#include "encoder/rate/encode_context.h"

namespace dcurve {

// Lengths tried (each only when shorter than the clip), and the whole clip as one chunk when
// it has at most kMaxWholeClipFrames frames: a short clip gains most from one chunk and costs
// little to decode whole; a long one keeps a decoder's window to at most 32 frames.
constexpr uint32_t kChunkCandidates[] = {16, 32};
constexpr uint32_t kMaxWholeClipFrames = 128;
constexpr double kChunkSlack = 0.02;

// Recodes model->residual (its grid, faces, curves and low-rank model kept) at each
// candidate length from the context's grid values, and leaves the chosen one in *model, its
// file in *file. *coded is what model->residual's payload codes (its Model prediction the
// one every length subtracts), and receives the chosen payload's plan and values.
// how: how each length is measured. Replan: planned again for its chunks (every coding
// order and cluster layout). Cut: the kept plan cut into chunks (chunk_cut.h) and coded with
// the same values, a pass of the coder instead of a plan, and only the length chosen planned
// again. Cut measures a short length larger than its own plan codes it (the values were
// snapped for predictors the cut replaces), so it keeps the whole clip more often.
enum class ChunkTrial { Replan, Cut };
bool choose_chunk_frames(Model* model, CodedResidual* coded, const EncodeContext& context, ChunkTrial how,
                         std::vector<uint8_t>* file, std::string* error);

}  // namespace dcurve
