// The floor anyone reaches: float32 positions as they are, and zstd of them. Both pay the
// Draco connectivity charge once.
#include <cstring>

#include "bench/baselines.h"
#include "bench/zstd_blob.h"

namespace dcurve::bench {
namespace {

size_t frame_bytes(const BenchContext& ctx) { return size_t(ctx.anim.vertex_count) * 3 * sizeof(float); }

std::vector<uint8_t> concatenated_frames(const BenchContext& ctx) {
  std::vector<uint8_t> raw(frame_bytes(ctx) * ctx.anim.frames.size());
  for (size_t f = 0; f < ctx.anim.frames.size(); ++f)
    std::memcpy(raw.data() + f * frame_bytes(ctx), ctx.anim.frames[f].data(), frame_bytes(ctx));
  return raw;
}

void split_frames(const BenchContext& ctx, const uint8_t* raw, std::vector<std::vector<float>>* decoded) {
  decoded->resize(ctx.anim.frames.size());
  for (size_t f = 0; f < decoded->size(); ++f) {
    (*decoded)[f].resize(size_t(ctx.anim.vertex_count) * 3);
    std::memcpy((*decoded)[f].data(), raw + f * frame_bytes(ctx), frame_bytes(ctx));
  }
}

}  // namespace

bool bench_raw_float32(const BenchContext& ctx, MethodResult* r, std::string*) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<uint8_t> raw = concatenated_frames(ctx);
  r->encode_seconds = seconds_since(start);
  std::vector<std::vector<float>> decoded;
  auto decode_all = [&]() {
    split_frames(ctx, raw.data(), &decoded);
    return true;
  };
  decode_all();
  set_measures(ctx, decoded, raw.size() + ctx.connectivity_charge, ctx.connectivity_charge, r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  r->settings = "little-endian float32 (decode = memcpy)";
  return true;
}

bool bench_raw_zstd(const BenchContext& ctx, MethodResult* r, std::string* error) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<uint8_t> raw = concatenated_frames(ctx);
  const std::vector<uint8_t> blob = zstd_pack(raw.data(), raw.size());
  r->encode_seconds = seconds_since(start);
  std::vector<uint8_t> unpacked;
  std::vector<std::vector<float>> decoded;
  auto decode_all = [&]() {
    if (!zstd_unpack(blob, raw.size(), &unpacked, error)) return false;
    split_frames(ctx, unpacked.data(), &decoded);
    return true;
  };
  if (!decode_all()) return false;
  set_measures(ctx, decoded, blob.size() + ctx.connectivity_charge, ctx.connectivity_charge, r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  r->settings = "zstd level " + std::to_string(kBaselineZstdLevel) + " of float32";
  return true;
}

}  // namespace dcurve::bench
