#include "codec/residual.h"

#include "codec/bytes.h"

namespace dcurve {
namespace {
uint64_t zigzag(int64_t v) { return uint64_t(v << 1) ^ uint64_t(v >> 63); }
int64_t unzigzag(uint64_t z) { return int64_t(z >> 1) ^ -int64_t(z & 1); }
}  // namespace

// Predictor: the same vertex in the previous frame; in frame 0, the previous vertex. The
// container's zstd does the entropy coding.
std::vector<uint8_t> encode_residuals(const Model& model, const std::vector<int32_t>& q) {
  const size_t n = size_t(model.meta.vertex_count) * 3;
  ByteWriter w;
  for (size_t i = 0; i < q.size(); ++i) {
    int64_t pred = i >= n ? q[i - n] : i >= 3 ? q[i - 3] : 0;
    w.varint(zigzag(int64_t(q[i]) - pred));
  }
  return std::move(w.data());
}

bool decode_residuals(const Model& model, std::vector<int32_t>* q, std::string* error) {
  const size_t n = size_t(model.meta.vertex_count) * 3;
  const size_t total = n * model.meta.frame_count;
  q->resize(total);
  ByteReader r(model.residual.payload.data(), model.residual.payload.size());
  for (size_t i = 0; i < total; ++i) {
    int64_t pred = i >= n ? (*q)[i - n] : i >= 3 ? (*q)[i - 3] : 0;
    int64_t v = pred + unzigzag(r.varint());
    if (!r.ok || v < INT32_MIN || v > INT32_MAX) {
      if (error) *error = "residual stream is truncated or out of range";
      return false;
    }
    (*q)[i] = int32_t(v);
  }
  if (r.remaining() != 0) {
    if (error) *error = "residual stream has trailing bytes";
    return false;
  }
  return true;
}

}  // namespace dcurve
