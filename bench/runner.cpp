#include "bench/runner.h"

#include <algorithm>
#include <stdexcept>

#include "bench/baselines.h"
#include "encoder/metrics.h"

namespace dcurve::bench {
namespace {

using MethodFn = bool (*)(const BenchContext&, MethodResult*, std::string*);

struct MethodEntry {
  const char* name;
  MethodFn run;
};

// dcurve first; the rest in the order the table shows them.
const MethodEntry kMethods[] = {
    {"dcurve", bench_dcurve},
    {"draco_per_frame", bench_draco_per_frame},
    {"draco_keyframes", bench_draco_keyframes},
    {"pca", bench_pca},
    {"quantized_delta", bench_quantized_delta},
    {"raw_float32", bench_raw_float32},
    {"raw_zstd", bench_raw_zstd},
};

}  // namespace

const std::vector<std::string>& all_methods() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const auto& m : kMethods) n.push_back(m.name);
    return n;
  }();
  return names;
}

InputResult run_bench(const std::string& name, const Animation& anim, double tolerance,
                      const std::vector<std::string>& methods, const std::function<void(double)>& progress,
                      int dcurve_effort) {
  std::string err;
  if (!validate_animation(anim, &err)) throw std::invalid_argument(name + ": " + err);
  if (!(tolerance > 0 && tolerance <= 0.5)) throw std::invalid_argument("tolerance must be in (0, 0.5]");
  if (dcurve_effort < kMinEffort || dcurve_effort > kMaxEffort) throw std::invalid_argument("dcurve effort out of range");
  std::vector<const MethodEntry*> chosen;
  for (const auto& m : kMethods)
    if (methods.empty() || std::find(methods.begin(), methods.end(), m.name) != methods.end()) chosen.push_back(&m);
  for (const auto& want : methods)
    if (std::find(all_methods().begin(), all_methods().end(), want) == all_methods().end())
      throw std::invalid_argument("unknown method '" + want + "'");
  const double L = bbox_diagonal(anim.frames[0]);
  if (!(L > 0)) throw std::invalid_argument(name + ": rest pose has a zero bounding box");

  InputResult out{name, tolerance, anim.vertex_count, uint32_t(anim.frames.size()), {}};
  DracoFrameCodec draco;
  const bool draco_ok = draco.init(anim.vertex_count, anim.faces, &err);
  const std::string draco_error = err;
  const BenchContext ctx{anim, tolerance, L, draco, draco.connectivity_bytes(), dcurve_effort};
  for (size_t i = 0; i < chosen.size(); ++i) {
    if (progress) progress(double(i) / double(chosen.size()));
    MethodResult r;
    r.method = chosen[i]->name;
    err.clear();
    // Every method charges Draco's connectivity size, so none runs without the calibration.
    const bool ok = draco_ok && chosen[i]->run(ctx, &r, &err);
    if (!ok) {
      r = MethodResult{};
      r.method = chosen[i]->name;
      r.settings = "failed: " + (draco_ok ? err : draco_error);
    }
    out.methods.push_back(r);
  }
  if (progress) progress(1.0);
  return out;
}

InputResult run_bench(const std::string& name, const Animation& anim, double tolerance,
                      const std::function<void(double)>& progress) {
  return run_bench(name, anim, tolerance, {}, progress);
}

}  // namespace dcurve::bench
