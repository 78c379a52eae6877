// Draco keyframes + linear interpolation: every k-th frame (and the last) a Draco file, the
// frames between interpolated linearly from the two decoded keyframes around them. The
// smallest total over k and one bit depth for all keyframes that meets the tolerance.
#include <algorithm>

#include "bench/baselines.h"
#include "bench/draco_per_frame.h"
#include "encoder/metrics.h"

namespace dcurve::bench {
namespace {

std::vector<size_t> keyframe_indices(size_t F, size_t k) {
  std::vector<size_t> keys;
  for (size_t f = 0; f < F; f += k) keys.push_back(f);
  if (keys.back() != F - 1) keys.push_back(F - 1);
  return keys;
}

// Fills every frame from the keyframe positions `key_xyz` (one per entry of `keys`).
void interpolate(const std::vector<size_t>& keys, const std::vector<std::vector<float>>& key_xyz,
                 std::vector<std::vector<float>>* frames) {
  for (size_t i = 0; i + 1 < keys.size(); ++i) {
    const size_t a = keys[i], b = keys[i + 1];
    for (size_t f = a; f <= b; ++f) {
      const double w = double(f - a) / double(b - a);
      auto& out = (*frames)[f];
      out.resize(key_xyz[i].size());
      for (size_t j = 0; j < out.size(); ++j) out[j] = float((1 - w) * key_xyz[i][j] + w * key_xyz[i + 1][j]);
    }
  }
  if (keys.size() == 1) (*frames)[0] = key_xyz[0];
}

struct KeyframeTrial {
  std::vector<std::vector<char>> files;
  uint64_t bytes = 0;
  double max_error = 0;
};

bool try_bits(const BenchContext& ctx, const std::vector<size_t>& keys, int bits, KeyframeTrial* t,
              std::string* error) {
  std::vector<std::vector<float>> key_xyz(keys.size()), frames(ctx.anim.frames.size());
  t->files.assign(keys.size(), {});
  t->bytes = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    if (!ctx.draco.encode(ctx.anim.frames[keys[i]].data(), bits, &t->files[i], error)) return false;
    if (!ctx.draco.decode(t->files[i], &key_xyz[i], error)) return false;
    t->bytes += t->files[i].size();
  }
  interpolate(keys, key_xyz, &frames);
  t->max_error = measure_error(ctx.anim, frames).max_error;
  return true;
}

}  // namespace

bool bench_draco_keyframes(const BenchContext& ctx, MethodResult* r, std::string* error) {
  const auto start = std::chrono::steady_clock::now();
  const size_t F = ctx.anim.frames.size();
  size_t best_k = 0;
  int best_bits = 0;
  KeyframeTrial best;
  for (size_t k : {1, 2, 3, 4, 5, 6, 8, 10, 12, 16, 20, 24, 32}) {
    if (k > 1 && k >= F) break;
    const std::vector<size_t> keys = keyframe_indices(F, k);
    // Interpolating exact keyframes is the best any bit depth can do; skip k past it.
    std::vector<std::vector<float>> exact_keys, frames(F);
    for (size_t key : keys) exact_keys.push_back(ctx.anim.frames[key]);
    interpolate(keys, exact_keys, &frames);
    if (measure_error(ctx.anim, frames).max_error > ctx.tolerance) continue;
    int lo = kDracoMinBits, hi = kDracoMaxBits + 1;
    KeyframeTrial found;
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      KeyframeTrial t;
      if (!try_bits(ctx, keys, mid, &t, error)) return false;
      if (t.max_error <= ctx.tolerance) {
        hi = mid;
        found = std::move(t);
      } else {
        lo = mid + 1;
      }
    }
    if (hi <= kDracoMaxBits && (best_k == 0 || found.bytes < best.bytes)) {
      best_k = k;
      best_bits = hi;
      best = std::move(found);
    }
  }
  if (best_k == 0) {
    // Nothing meets the tolerance: report every frame at the finest bits, marked as failing.
    best_k = 1;
    best_bits = kDracoMaxBits;
    if (!try_bits(ctx, keyframe_indices(F, 1), best_bits, &best, error)) return false;
  }
  r->encode_seconds = seconds_since(start);

  const std::vector<size_t> keys = keyframe_indices(F, best_k);
  std::vector<std::vector<float>> key_xyz(keys.size()), decoded(F);
  bool verify = true;
  auto decode_all = [&]() {
    for (size_t i = 0; i < keys.size(); ++i)
      if (!ctx.draco.decode(best.files[i], &key_xyz[i], error, verify)) return false;
    interpolate(keys, key_xyz, &decoded);
    return true;
  };
  if (!decode_all()) return false;
  verify = false;
  set_measures(ctx, decoded, best.bytes, uint64_t(keys.size()) * ctx.draco.connectivity_bytes(), r);
  r->decode_vertices_per_second = decode_rate(ctx, decode_all);
  r->settings = "every " + std::to_string(best_k) + " frames (" + std::to_string(keys.size()) +
                " keyframes), bits " + std::to_string(best_bits) + ", level 10";
  return true;
}

}  // namespace dcurve::bench
