// Figures every method reports the same way.
#include <algorithm>
#include <limits>

#include "bench/baselines.h"
#include "encoder/metrics.h"

namespace dcurve::bench {

void set_measures(const BenchContext& ctx, const std::vector<std::vector<float>>& decoded, uint64_t bytes,
                  uint64_t connectivity_bytes, MethodResult* r) {
  const ErrorStats e = measure_error(ctx.anim, decoded);
  r->bytes = bytes;
  r->connectivity_bytes = connectivity_bytes;
  r->bpvf = 8.0 * double(bytes) / (double(ctx.anim.vertex_count) * double(ctx.anim.frames.size()));
  r->max_error = e.max_error;
  r->rmse = e.rmse;
  r->kg_error_pct = e.kg_error_pct;
  r->meets_tolerance = e.max_error <= ctx.tolerance;
}

double decode_rate(const BenchContext& ctx, const std::function<bool()>& decode_all) {
  // Three runs, or fewer once a second has been spent: enough to skip a cold first run
  // without making slow decoders dominate the bench's own time.
  double best = std::numeric_limits<double>::infinity(), spent = 0;
  for (int run = 0; run < 3 && spent < 1.0; ++run) {
    const auto start = std::chrono::steady_clock::now();
    if (!decode_all()) return 0;
    const double s = seconds_since(start);
    best = std::min(best, s);
    spent += s;
  }
  const double vertex_frames = double(ctx.anim.vertex_count) * double(ctx.anim.frames.size());
  return best > 0 ? vertex_frames / best : 0;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace dcurve::bench
