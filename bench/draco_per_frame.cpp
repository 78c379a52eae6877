#include "bench/draco_per_frame.h"

#include <algorithm>

#include "encoder/metrics.h"

namespace dcurve::bench {

bool choose_draco_per_frame(const BenchContext& ctx, DracoPerFrameChoice* out, std::string* error) {
  const size_t F = ctx.anim.frames.size();
  std::vector<int> lo(F, kDracoMinBits), hi(F, kDracoMaxBits + 1);
  out->files.assign(F, {});
  // Frames not under test this round decode as the input itself, so they read as zero error.
  std::vector<std::vector<float>> decoded = ctx.anim.frames;
  std::vector<char> file;
  for (;;) {
    std::vector<size_t> active;
    for (size_t f = 0; f < F; ++f)
      if (lo[f] < hi[f]) active.push_back(f);
    if (active.empty()) break;
    std::vector<std::vector<char>> trial(F);
    for (size_t f : active) {
      const int mid = (lo[f] + hi[f]) / 2;
      if (!ctx.draco.encode(ctx.anim.frames[f].data(), mid, &trial[f], error)) return false;
      if (!ctx.draco.decode(trial[f], &decoded[f], error)) return false;
    }
    const ErrorStats e = measure_error(ctx.anim, decoded);
    for (size_t f : active) {
      const int mid = (lo[f] + hi[f]) / 2;
      if (e.max_error_per_frame[f] <= ctx.tolerance) {
        hi[f] = mid;
        out->files[f] = std::move(trial[f]);
      } else {
        lo[f] = mid + 1;
      }
      decoded[f] = ctx.anim.frames[f];
    }
  }
  out->bits.assign(F, 0);
  out->all_meet = true;
  for (size_t f = 0; f < F; ++f) {
    if (hi[f] > kDracoMaxBits) {
      out->all_meet = false;
      hi[f] = kDracoMaxBits;
      if (!ctx.draco.encode(ctx.anim.frames[f].data(), kDracoMaxBits, &out->files[f], error)) return false;
    }
    out->bits[f] = hi[f];
    if (!ctx.draco.decode(out->files[f], &decoded[f], error)) return false;
  }
  out->max_error = measure_error(ctx.anim, decoded).max_error_per_frame;
  return true;
}

bool bench_draco_per_frame(const BenchContext& ctx, MethodResult* r, std::string* error) {
  const auto start = std::chrono::steady_clock::now();
  DracoPerFrameChoice choice;
  if (!choose_draco_per_frame(ctx, &choice, error)) return false;
  r->encode_seconds = seconds_since(start);
  const size_t F = ctx.anim.frames.size();
  std::vector<std::vector<float>> decoded(F);
  bool verify = true;
  auto decode_all = [&]() {
    for (size_t f = 0; f < F; ++f)
      if (!ctx.draco.decode(choice.files[f], &decoded[f], error, verify)) return false;
    return true;
  };
  if (!decode_all()) return false;
  verify = false;
  uint64_t bytes = 0;
  for (const auto& file : choice.files) bytes += file.size();
  set_measures(ctx, decoded, bytes, uint64_t(F) * ctx.draco.connectivity_bytes(), r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  const auto [min_bits, max_bits] = std::minmax_element(choice.bits.begin(), choice.bits.end());
  r->settings = "bits " + std::to_string(*min_bits) + ".." + std::to_string(*max_bits) +
                " per frame, level 10, connectivity in every frame";
  return true;
}

}  // namespace dcurve::bench
