// Reading one chunk of a fast residual payload (format 4, format_spec/residual.md section
// 10) frame by frame: the runtime decodes only up to the frame it needs and holds the frames
// the predictors read, not the chunk.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "codec/common/fast_fit.h"
#include "codec/common/fast_residual.h"
#include "codec/common/fast_traversal.h"

namespace dcurve {

class FastChunkDecoder {
 public:
  // Parses the frame table of a chunk of `frames` frames of V vertices (its `size` bytes)
  // and decompresses its streams. has_model: the file has a Model prediction; traversal:
  // fast_traversal of the file's faces, which must outlive the decoding; allow_fit: the chunk
  // is a low-rank basis, whose kinds may carry the Fit flag. False with a message when the
  // table or a stream is malformed; reads nothing outside the bytes.
  bool open(const uint8_t* bytes, size_t size, uint32_t V, uint32_t frames, bool has_model,
            const FastTraversal* traversal, std::string* error, bool allow_fit = false);
  // Whether some frame has the Fit flag; those read set_fit's weights (fast_fit of the
  // chunk's frame 0), which must outlive their decoding.
  bool uses_fit() const;
  void set_fit(const FastFit* fit) { fit_ = fit; }
  // How many frames from next() on have exactly the kind None + spatial + Fit (a basis's
  // vectors); decode_fit_frames decodes up to that many side by side into out (count * V * 3
  // values), checked as decode_frame checks each: one pass over the positions reads each Fit
  // set once for all of them.
  uint32_t fit_run() const;
  bool decode_fit_frames(uint32_t count, int32_t* out, std::string* error);
  // Moves past `count` frames from next() without decoding them, their tokens stepped over
  // (their values and checksums unchecked): a seek starts at the last frame before its
  // target that reads no earlier frame. False when the tokens run out first.
  bool skip_frames(uint32_t count, std::string* error);
  // Local frame next() is the one decode_frame decodes; frames go in order from 0.
  uint32_t next() const { return next_; }
  uint32_t frames() const { return uint32_t(kinds_.size()); }
  fast_residual::FrameKind kind(uint32_t k) const { return fast_residual::base_kind(kinds_[k]); }
  // Decodes frame next() into out (V * 3 values): q1, q2 the frames one and two before it,
  // M and M1 the Model prediction of this frame and the one before, each null when its
  // kind does not read it. Checks the frame's checksum, and after the last frame that the
  // streams were used up. Not for a Fit frame (decode_fit_frames).
  bool decode_frame(const int32_t* q1, const int32_t* q2, const int32_t* M, const int32_t* M1, int32_t* out,
                    std::string* error);
  size_t memory_bytes() const;

 private:
  bool add_residuals(int32_t* out);
  template <class Base>
  bool add_spatial_residuals(const Base& base, int32_t* out, bool smooth);
  bool add_spatial_frame(fast_residual::FrameKind kind, const int32_t* q1, const int32_t* q2, const int32_t* M,
                         const int32_t* M1, int32_t* out, bool smooth);
  bool finish_frame(const int32_t* out, std::string* error);

  const FastTraversal* traversal_ = nullptr;
  const FastFit* fit_ = nullptr;
  // decode_fit_frames: per position, the frames' values side by side (uninitialized: every
  // lane is written before it is read), kept for the next group of Fit frames.
  std::unique_ptr<int32_t[]> lanes_;
  size_t lanes_size_ = 0;
  uint32_t V_ = 0, next_ = 0;
  std::vector<uint8_t> kinds_;
  std::vector<uint32_t> op_counts_, checksums_;
  std::vector<uint8_t> ops_, values_;
  size_t op_pos_ = 0, value_pos_ = 0;
};

// Decodes every frame of one chunk into q (frames * V * 3 values); model: the chunk's Model
// prediction, frames * V * 3 values, or null without one. basis_faces: the file's faces when
// the chunk is a low-rank basis (its kinds may carry the Fit flag), else null.
bool decode_fast_chunk(const FastTraversal& traversal, uint32_t V, const uint8_t* bytes, size_t size, uint32_t frames,
                       const int32_t* model, int32_t* q, std::string* error,
                       const std::vector<uint32_t>* basis_faces = nullptr);

}  // namespace dcurve
