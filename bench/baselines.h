// The methods compared by `dcurve bench`, one per file. Each encodes the whole animation
// at the context's tolerance, decodes its own bytes and reports the measured figures.
#pragma once
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "bench/draco_frame.h"
#include "bench/runner.h"
#include "encoder/io/frames.h"

namespace dcurve::bench {

struct BenchContext {
  const Animation& anim;
  double tolerance;                 // max error, fraction of L
  double diagonal;                  // L, model units
  const DracoFrameCodec& draco;     // calibrated on anim's connectivity
  uint64_t connectivity_charge;     // Draco edgebreaker connectivity bytes, paid once by non-Draco methods
  int dcurve_effort;                // EncodeOptions::effort of the dcurve method
};

// Each returns false with *error set when the method cannot run at all; otherwise fills
// *result (meets_tolerance false when no setting reaches the tolerance).
bool bench_dcurve(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_draco_per_frame(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_draco_keyframes(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_pca(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_quantized_delta(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_raw_float32(const BenchContext& ctx, MethodResult* result, std::string* error);
bool bench_raw_zstd(const BenchContext& ctx, MethodResult* result, std::string* error);

// Fills the size and error fields of *r from the decoded frames (measure_error of
// encoder/metrics.h) and sets meets_tolerance.
void set_measures(const BenchContext& ctx, const std::vector<std::vector<float>>& decoded, uint64_t bytes,
                  uint64_t connectivity_bytes, MethodResult* r);

// Vertices per second of `decode_all` (which decodes every frame), the best of a few runs
// so a cold cache does not count; 0 when it fails.
double decode_rate(const BenchContext& ctx, const std::function<bool()>& decode_all);

// Seconds since `start`.
double seconds_since(std::chrono::steady_clock::time_point start);

}  // namespace dcurve::bench
