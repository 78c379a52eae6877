// FastChunkDecoder::decode_fit_frames: a low-rank basis's vectors (format_spec/residual.md
// section 10.7) decoded side by side. Every vector shares the mean's Fit sets and weights, so
// one pass over the positions reads each set once and applies it to all of them: a tight loop
// over contiguous lanes instead of a gather per vector.
#include <algorithm>
#include <string>
#include <vector>

#include "codec/common/error.h"
#include "codec/common/low_rank.h"
#include "codec/decompress/fast_residual_decoder.h"
#include "codec/decompress/fast_tokens.h"

// The lane loop is a widening multiply-add, which x86-64's baseline (SSE2) cannot vectorize:
// an AVX2 clone is picked at load time where the CPU has it (same results, integer arithmetic).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(__EMSCRIPTEN__)
#define DCURVE_LANE_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define DCURVE_LANE_CLONES
#endif

namespace dcurve {

using namespace fast_residual;
using namespace fast_tokens;

uint32_t FastChunkDecoder::fit_run() const {
  uint32_t k = next_;
  while (k < kinds_.size() && kinds_[k] == (kFitFlag | kSpatialFlag)) ++k;
  return k - next_;
}

namespace {

// The Fit prediction of lanes l < L of position p (into pred) from the lanes of the
// positions before it. Every lane is a basis value (|x| <= 2^24), so the differences fit in
// int32 and a prediction within 2^34.
DCURVE_LANE_CLONES void predict_lanes(const FastFit& fit, size_t p, const int32_t* lanes, size_t L, int64_t* pred) {
  const uint32_t begin = fit.offsets[p], end = fit.offsets[p + 1];
  std::fill(pred, pred + L, 0);
  if (begin == end) return;
  const int32_t* e0 = lanes + size_t(fit.refs[begin]) * L;
  for (uint32_t k = begin + 1; k < end; ++k) {
    const int32_t w = fit.weights[k];
    const int32_t* x = lanes + size_t(fit.refs[k]) * L;
    for (size_t l = 0; l < L; ++l) pred[l] += int64_t(w) * int64_t(x[l] - e0[l]);  // a widening multiply
  }
  for (size_t l = 0; l < L; ++l) pred[l] = e0[l] + round_shift(pred[l], 16);
}

}  // namespace

bool FastChunkDecoder::decode_fit_frames(uint32_t count, int32_t* out, std::string* error) {
  const FastTraversal& t = *traversal_;
  if (count == 0 || count > fit_run()) return fail(error, "fast residual frames are not all Fit frames");
  if (!traversal_ || t.order.size() != V_ || !fit_ || fit_->offsets.size() != size_t(V_) + 1)
    return fail(error, "fast residual frame needs the vertex traversal and Fit weights, which were not supplied");
  const size_t L = size_t(count) * 3, n = size_t(V_) * 3;
  FrameTokens starts;
  if (!token_starts(ops_, values_, op_counts_, next_, count, op_pos_, value_pos_, &starts))
    return fail(error, "fast residual frame " + std::to_string(next_) + " has fewer values than its ops name");
  std::vector<OpCursor> cursors;
  std::vector<size_t> value_pos(starts.value_begin.begin(), starts.value_begin.end() - 1);
  for (uint32_t j = 0; j < count; ++j) {
    cursors.push_back(OpCursor{ops_, starts.op_begin[j], starts.op_begin[j + 1], V_});
    if (!cursors.back().next()) return fail(error, "fast residual frame " + std::to_string(next_ + j) + " is corrupted");
  }
  if (lanes_size_ < size_t(V_) * L) {
    lanes_size_ = size_t(V_) * L;
    lanes_.reset(new int32_t[lanes_size_]);
  }
  int32_t* lanes = lanes_.get();
  std::vector<int64_t> sums(L);
  for (uint32_t p = 0; p < V_; ++p) {
    int64_t* v = sums.data();  // predictions, then values
    predict_lanes(*fit_, p, lanes, L, v);
    for (uint32_t j = 0; j < count; ++j) {
      OpCursor& c = cursors[j];
      if (c.slot != p) continue;
      for (int a = 0; a < 3; ++a) {
        int64_t r = 0;
        if ((c.mask >> a & 1) && !read_value(values_.data(), starts.value_begin[j + 1], &value_pos[j], &r))
          return fail(error, "fast residual frame " + std::to_string(next_ + j) + " has a malformed value");
        v[j * 3 + size_t(a)] += r;
      }
      if (!c.next()) return fail(error, "fast residual frame " + std::to_string(next_ + j) + " is corrupted");
    }
    int32_t* x = lanes + size_t(p) * L;
    for (size_t l = 0; l < L; ++l) {
      if (v[l] < -kMaxFitValue || v[l] > kMaxFitValue)
        return fail(error, "fast residual frame " + std::to_string(next_ + l / 3) + " decodes out of range");
      x[l] = int32_t(v[l]);
    }
    int32_t* o = out + size_t(t.order[p]) * 3;
    for (uint32_t j = 0; j < count; ++j, o += n) o[0] = x[j * 3], o[1] = x[j * 3 + 1], o[2] = x[j * 3 + 2];  // no memcpy call per 12 bytes
  }
  op_pos_ = starts.op_begin[count];
  for (uint32_t j = 0; j < count; ++j) {
    if (cursors[j].slot != V_) return fail(error, "fast residual frame " + std::to_string(next_) + " is corrupted");
    value_pos_ = starts.value_begin[j + 1];
    if (!finish_frame(out + j * n, error)) return false;
  }
  return true;
}

}  // namespace dcurve
