#include "codec/decompress/fast_residual_decoder.h"

#include <algorithm>

#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/common/error.h"
#include "codec/common/residual_walk.h"
#include "codec/decompress/fast_tokens.h"
#include "codec/decompress/zstd_frame.h"

namespace dcurve {

using namespace fast_residual;
using namespace fast_tokens;

// Fit frames decoded side by side at most: 24 lanes of int64 sums stay in registers, and the
// lane buffer (V * 24 values) is reused from group to group (measured on horse-gallop's 24
// vectors: 8 beats 4, 12 and all 24).
constexpr uint32_t kFitFramesSideBySide = 8;

size_t FastChunkDecoder::memory_bytes() const {
  return sizeof(*this) + kinds_.capacity() + (op_counts_.capacity() + checksums_.capacity()) * 4 + ops_.capacity() +
         values_.capacity() + lanes_size_ * sizeof(int32_t);
}

namespace {
// A stream of the chunk (coding byte, raw size, stored bytes) into out; max_raw bounds the
// raw size before anything is allocated.
bool read_stream(ByteReader& r, uint64_t max_raw, std::vector<uint8_t>* out, std::string* error) {
  const uint8_t coding = r.u8();
  const uint64_t raw = r.varint();
  if (!r.ok) return fail(error, "fast residual chunk is truncated");
  if (coding > kStreamZstd) return fail(error, "fast residual stream coding is unknown");
  if (raw > max_raw) return fail(error, "fast residual stream claims more bytes than its frames can hold");
  uint64_t stored = raw;
  if (coding == kStreamZstd) {
    stored = r.varint();
    if (!r.ok) return fail(error, "fast residual chunk is truncated");
    if (!zstd_size_plausible(raw, stored))
      return fail(error, "fast residual stream claims an implausible decompressed size");
  }
  const uint8_t* p = r.take(size_t(std::min<uint64_t>(stored, SIZE_MAX)));
  if (!p || stored > SIZE_MAX) return fail(error, "fast residual stream runs past the end of its chunk");
  if (coding == kStreamRaw) {
    out->assign(p, p + stored);
    return true;
  }
  if (!decompress_exactly(p, size_t(stored), raw, out))
    return fail(error, "fast residual stream does not decompress to its size");
  return true;
}

}  // namespace

bool FastChunkDecoder::open(const uint8_t* bytes, size_t size, uint32_t V, uint32_t frames, bool has_model,
                            const FastTraversal* traversal, std::string* error, bool allow_fit) {
  traversal_ = traversal;
  fit_ = nullptr;
  V_ = V;
  next_ = 0;
  op_pos_ = value_pos_ = 0;
  kinds_.clear();
  ByteReader r(bytes, size);
  const uint8_t* kinds = r.take(frames);
  if (!kinds) return fail(error, "fast residual chunk is truncated");
  for (uint32_t k = 0; k < frames; ++k)
    if (!kind_usable(kinds[k], k, has_model, allow_fit))
      return fail(error, "fast residual frame " + std::to_string(k) + " has a predictor it cannot use");
  op_counts_.resize(frames);
  uint64_t ops = 0;
  for (uint32_t& count : op_counts_) {
    const uint64_t c = r.varint();
    if (!r.ok || c > V) return fail(error, "fast residual op count is out of range");
    count = uint32_t(c);
    ops += c;
  }
  checksums_.resize(frames);
  for (uint32_t& c : checksums_) c = r.u32();
  if (!r.ok) return fail(error, "fast residual chunk is truncated");
  const uint64_t coords = uint64_t(V) * 3 * frames;
  if (!read_stream(r, ops, &ops_, error) || !read_stream(r, coords * 6, &values_, error))
    return false;
  if (ops_.size() != ops) return fail(error, "fast residual op stream disagrees with the op counts");
  if (r.remaining() != 0) return fail(error, "fast residual chunk has bytes after its streams");
  kinds_.assign(kinds, kinds + frames);
  return true;
}


bool FastChunkDecoder::skip_frames(uint32_t count, std::string* error) {
  if (count > kinds_.size() - next_) return fail(error, "fast residual chunk has fewer frames to skip");
  for (; count > 0; --count, ++next_)
    if (!skip_frame_tokens(ops_, values_, op_counts_[next_], &op_pos_, &value_pos_))
      return fail(error, "fast residual frames to skip have fewer values than their ops name");
  return true;
}

// The frame's residuals added to its base prediction in out, in vertex-id order.
bool FastChunkDecoder::add_residuals(int32_t* out) {
  OpCursor c{ops_, op_pos_, op_pos_ + op_counts_[next_], V_};
  while (c.next() && c.slot < V_) {
    for (int a = 0; a < 3; ++a) {
      if (!(c.mask >> a & 1)) continue;
      int64_t r = 0;
      int32_t& x = out[size_t(c.slot) * 3 + size_t(a)];
      if (!read_value(values_.data(), values_.size(), &value_pos_, &r) || !in_int32(int64_t(x) + r)) return false;
      x = int32_t(int64_t(x) + r);
    }
  }
  op_pos_ = c.pos;
  return c.slot == V_;
}

namespace {
// Base predictions P of value i (vertex-major, int64, clamped as 10.2 says) computed where a
// spatial frame reads them: a correction e = q - P of an earlier position comes back from the
// decoded q and the frames P reads, so no frame-sized buffer of corrections is kept.
struct NoBase {
  int64_t operator()(size_t) const { return 0; }
};
struct CopyBase {  // Previous (q1) or Model (M)
  const int32_t* src;
  int64_t operator()(size_t i) const { return src[i]; }
};
struct LinearBase {
  const int32_t *q1, *q2;
  int64_t operator()(size_t i) const { return clamp_int32(2 * int64_t(q1[i]) - q2[i]); }
};
struct ModelDeltaBase {
  const int32_t *M, *q1, *M1;
  int64_t operator()(size_t i) const { return clamp_int32(int64_t(M[i]) + q1[i] - M1[i]); }
};

// The corrections of the vertex at an earlier position (its values q already in out).
template <class Base>
inline void corrections_at(const Base& base, const int32_t* out, uint32_t v, int64_t* e) {
  const size_t i = size_t(v) * 3;
  for (int a = 0; a < 3; ++a) e[a] = int64_t(out[i + size_t(a)]) - base(i + size_t(a));
}

// What the traversal predicts for position i's three axes from the corrections of the
// positions before it: fast_spatial for the three at once, the type read once.
template <class Base>
inline void predict_position(FastSpatial type, const uint32_t* r, const FastTraversal& t, const Base& base,
                             const int32_t* out, int64_t* p) {
  int64_t x[3], y[3], z[3];
  switch (type) {
    case FastSpatial::Copy:
      corrections_at(base, out, t.order[r[0]], p);
      break;
    case FastSpatial::Mean:
      corrections_at(base, out, t.order[r[0]], x);
      corrections_at(base, out, t.order[r[1]], y);
      for (int a = 0; a < 3; ++a) p[a] = (x[a] + y[a] + 1) >> 1;
      break;
    case FastSpatial::Parallelogram:
      corrections_at(base, out, t.order[r[0]], x);
      corrections_at(base, out, t.order[r[1]], y);
      corrections_at(base, out, t.order[r[2]], z);
      for (int a = 0; a < 3; ++a) p[a] = x[a] + y[a] - z[a];
      break;
    default:
      for (int a = 0; a < 3; ++a) p[a] = 0;
  }
}
}  // namespace

bool FastChunkDecoder::uses_fit() const { return std::any_of(kinds_.begin(), kinds_.end(), is_fit); }

// Spatial frames: in traversal order, each position's residual (zero unless the ops name it)
// plus what the traversal predicts from the positions before it is the correction of the
// base prediction. One pass; out needs no prediction written first.
template <class Base>
bool FastChunkDecoder::add_spatial_residuals(const Base& base, int32_t* out, bool smooth) {
  const FastTraversal& t = *traversal_;
  OpCursor c{ops_, op_pos_, op_pos_ + op_counts_[next_], V_};
  if (!c.next()) return false;
  for (uint32_t i = 0; i < V_; ++i) {
    FastSpatial type = FastSpatial(t.type[i]);
    if (smooth && type == FastSpatial::Parallelogram) type = FastSpatial::Mean;
    int64_t x[3];
    predict_position(type, &t.refs[size_t(i) * 3], t, base, out, x);
    if (i == c.slot) {
      for (int a = 0; a < 3; ++a) {
        int64_t r = 0;
        if ((c.mask >> a & 1) && !read_value(values_.data(), values_.size(), &value_pos_, &r)) return false;
        x[a] += r;
      }
      if (!c.next()) return false;
    }
    const size_t o = size_t(t.order[i]) * 3;
    const int64_t q0 = base(o) + x[0], q1 = base(o + 1) + x[1], q2 = base(o + 2) + x[2];
    // Rejecting q outside int32 also keeps every e within 2^33, so the sums stay small.
    if (!in_int32(q0) || !in_int32(q1) || !in_int32(q2)) return false;
    out[o] = int32_t(q0);
    out[o + 1] = int32_t(q1);
    out[o + 2] = int32_t(q2);
  }
  op_pos_ = c.pos;
  return true;
}

// add_spatial_residuals for the frame's base kind.
bool FastChunkDecoder::add_spatial_frame(FrameKind kind, const int32_t* q1, const int32_t* q2, const int32_t* M,
                                         const int32_t* M1, int32_t* out, bool smooth) {
  switch (kind) {
    case FrameKind::Previous: return add_spatial_residuals(CopyBase{q1}, out, smooth);
    case FrameKind::Linear: return add_spatial_residuals(LinearBase{q1, q2}, out, smooth);
    case FrameKind::Model: return add_spatial_residuals(CopyBase{M}, out, smooth);
    case FrameKind::ModelDelta: return add_spatial_residuals(ModelDeltaBase{M, q1, M1}, out, smooth);
    default: return add_spatial_residuals(NoBase{}, out, smooth);
  }
}

bool FastChunkDecoder::decode_frame(const int32_t* q1, const int32_t* q2, const int32_t* M, const int32_t* M1,
                                    int32_t* out, std::string* error) {
  if (next_ >= kinds_.size()) return fail(error, "fast residual chunk has no more frames");
  const uint8_t k = kinds_[next_];
  const bool spatial = has_spatial(k);
  if (spatial && (!traversal_ || traversal_->order.size() != V_))
    return fail(error, "fast residual frame needs the vertex traversal, which was not supplied");
  if (is_fit(k)) return fail(error, "internal error: a Fit frame is decoded by decode_fit_frames");
  if (!spatial) predict_frame(kind(next_), q1, q2, M, M1, size_t(V_) * 3, out);
  if (!(spatial ? add_spatial_frame(kind(next_), q1, q2, M, M1, out, is_smooth(k)) : add_residuals(out)))
    return fail(error, "fast residual frame " + std::to_string(next_) + " is corrupted or decodes out of range");
  return finish_frame(out, error);
}

// Frame next()'s checksum over its values out, then past it; after the last frame, that the
// values were used up.
bool FastChunkDecoder::finish_frame(const int32_t* out, std::string* error) {
  if (kVerifyChecksums && residual_walk::values_checksum(out, size_t(V_) * 3) != checksums_[next_])
    return fail(error, "fast residual frame " + std::to_string(next_) +
                           " decodes to other values than were coded (checksum mismatch)");
  if (++next_ == kinds_.size() && value_pos_ != values_.size())
    return fail(error, "fast residual chunk has values left after its last frame");
  return true;
}

bool decode_fast_chunk(const FastTraversal& traversal, uint32_t V, const uint8_t* bytes, size_t size, uint32_t frames,
                       const int32_t* model, int32_t* q, std::string* error, const std::vector<uint32_t>* basis_faces) {
  FastChunkDecoder chunk;
  if (!chunk.open(bytes, size, V, frames, model != nullptr, &traversal, error, basis_faces != nullptr)) return false;
  const size_t n = size_t(V) * 3;
  FastFit fit;
  for (uint32_t k = 0; k < frames; ++k) {
    if (k == 1 && chunk.uses_fit()) {  // frame 0 is the shape Fit is weighted by
      fit = fast_fit(*basis_faces, traversal, q);
      chunk.set_fit(&fit);
    }
    // Fit frames side by side, a few at a time: their lanes stay in registers and cache.
    if (const uint32_t run = std::min(chunk.fit_run(), kFitFramesSideBySide)) {
      if (!chunk.decode_fit_frames(run, q + k * n, error)) return false;
      k += run - 1;
      continue;
    }
    const int32_t* q1 = k >= 1 ? q + (k - 1) * n : nullptr;
    const int32_t* q2 = k >= 2 ? q + (k - 2) * n : nullptr;
    const int32_t* M = model ? model + k * n : nullptr;
    const int32_t* M1 = model && k >= 1 ? model + (k - 1) * n : nullptr;
    if (!chunk.decode_frame(q1, q2, M, M1, q + k * n, error)) return false;
  }
  return true;
}

}  // namespace dcurve
