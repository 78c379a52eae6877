#include "bench/zstd_blob.h"

#include <zstd.h>

#include <cmath>

namespace dcurve::bench {

std::vector<uint8_t> zstd_pack(const void* data, size_t size, int level) {
  std::vector<uint8_t> out(ZSTD_compressBound(size));
  const size_t n = ZSTD_compress(out.data(), out.size(), data, size, level);
  out.resize(ZSTD_isError(n) ? 0 : n);
  return out;
}

bool zstd_unpack(const std::vector<uint8_t>& blob, size_t expected_size, std::vector<uint8_t>* out,
                 std::string* error) {
  out->resize(expected_size);
  const size_t n = ZSTD_decompress(out->data(), out->size(), blob.data(), blob.size());
  if (ZSTD_isError(n) || n != expected_size) {
    if (error) *error = "zstd payload does not decompress to " + std::to_string(expected_size) + " bytes";
    return false;
  }
  return true;
}

void append_int32_le(const std::vector<int32_t>& values, std::vector<uint8_t>* out) {
  out->reserve(out->size() + values.size() * 4);
  for (int32_t v : values) {
    const uint32_t u = uint32_t(v);
    for (int b = 0; b < 4; ++b) out->push_back(uint8_t(u >> (8 * b)));
  }
}

std::vector<int32_t> read_int32_le(const uint8_t* data, size_t count) {
  std::vector<int32_t> out(count);
  for (size_t i = 0; i < count; ++i) {
    uint32_t u = 0;
    for (int b = 0; b < 4; ++b) u |= uint32_t(data[4 * i + b]) << (8 * b);
    out[i] = int32_t(u);
  }
  return out;
}

std::vector<uint8_t> to_byte_planes(const std::vector<uint8_t>& le) {
  const size_t n = le.size() / 4;
  std::vector<uint8_t> planes(le.size());
  for (size_t i = 0; i < n; ++i)
    for (size_t b = 0; b < 4; ++b) planes[b * n + i] = le[4 * i + b];
  return planes;
}

std::vector<uint8_t> from_byte_planes(const std::vector<uint8_t>& planes) {
  const size_t n = planes.size() / 4;
  std::vector<uint8_t> le(planes.size());
  for (size_t i = 0; i < n; ++i)
    for (size_t b = 0; b < 4; ++b) le[4 * i + b] = planes[b * n + i];
  return le;
}

bool quantize(double x, double step, int32_t* q) {
  const double g = std::nearbyint(x / step);
  if (!(std::fabs(g) <= 2147483647.0)) return false;
  *q = int32_t(g);
  return true;
}

}  // namespace dcurve::bench
