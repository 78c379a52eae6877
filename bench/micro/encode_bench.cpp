// Encode time and file size against tolerance, beside the simplest baseline measured in the
// same run (quantized temporal delta, bench/baselines.h). Inputs: the built-in rope-small
// scene (simulated once) and, when found, horse-gallop from the external corpus
// (DCURVE_CORPUS_EXT or ../shared/corpus-ext). DCURVE_ENCODE_BENCH_INPUTS adds inputs, a
// colon-separated list of built-in scene names or frame folders: the full-size rope
// (issue #8's 15k-vertex, 100-frame case) is "rope", or a folder `dcurve simulate --scene
// rope` wrote, which skips the minutes of simulation. At 1e-3 each input is also encoded at
// the lower efforts (EncodeOptions::effort), with their bytes and encode seconds as ratios
// to the default effort's, measured just before in the same run.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "bench/runner.h"
#include "encoder/encoder.h"
#include "corpus/sim/scene.h"

namespace {
using namespace dcurve;

const Animation* input(const std::string& name) {
  static std::map<std::string, Animation> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second.frames.empty() ? nullptr : &it->second;
  Animation& a = cache[name];
  std::string err;
  Scene scene;
  if (std::filesystem::is_directory(name)) {
    if (!read_frame_folder(name, &a, &err)) a = {};
  } else if (builtin_scene(name, &scene, &err)) {
    if (!simulate_scene(scene, &a, {}, &err)) a = {};
  } else {
    const char* env = std::getenv("DCURVE_CORPUS_EXT");
    const std::string dir = std::string(env ? env : "../shared/corpus-ext") + "/" + name;
    if (!std::filesystem::is_directory(dir) || !read_frame_folder(dir, &a, &err)) a = {};
  }
  return a.frames.empty() ? nullptr : &a;
}

// The default effort's encode seconds and bytes per input, for the lower efforts' ratios.
std::map<std::string, std::pair<double, double>>& default_effort() {
  static std::map<std::string, std::pair<double, double>> results;
  return results;
}

void BM_Encode(benchmark::State& state, const std::string& name, double tolerance, int effort) {
  const Animation* anim = input(name);
  if (!anim) {
    state.SkipWithError(("input not found: " + name).c_str());
    return;
  }
  EncodeOptions opt;
  opt.tolerance = tolerance;
  opt.effort = effort;
  EncodeReport rep;
  for (auto _ : state) {
    std::vector<uint8_t> bytes;
    std::string err;
    if (!encode_animation(*anim, opt, &bytes, &rep, &err)) {
      state.SkipWithError(err.c_str());
      return;
    }
  }
  const bench::InputResult base = bench::run_bench(name, *anim, tolerance, {"quantized_delta"}, {});
  const double vf = double(anim->vertex_count) * double(anim->frames.size());
  state.counters["bytes"] = double(rep.bytes);
  state.counters["bpvf"] = rep.bpvf;
  state.counters["max_error"] = rep.error.max_error;
  state.counters["vs_quantized_delta"] = double(rep.bytes) / double(base.methods.at(0).bytes);
  state.counters["vertex_frames_per_s"] = benchmark::Counter(vf, benchmark::Counter::kIsIterationInvariantRate);
  const std::string key = name + "/" + std::to_string(tolerance);
  if (effort == EncodeOptions().effort) {
    default_effort()[key] = {rep.encode_seconds, double(rep.bytes)};
  } else if (default_effort().count(key)) {
    state.counters["seconds_vs_default"] = rep.encode_seconds / default_effort()[key].first;
    state.counters["bytes_vs_default"] = double(rep.bytes) / default_effort()[key].second;
  }
}

void register_all() {
  std::vector<std::string> names{"rope-small", "horse-gallop"};
  if (const char* extra = std::getenv("DCURVE_ENCODE_BENCH_INPUTS")) {
    std::string list(extra);
    for (size_t start = 0; start <= list.size();) {
      const size_t end = std::min(list.find(':', start), list.size());
      if (end > start) names.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  const int standard = EncodeOptions().effort;
  for (const std::string& name : names) {
    std::vector<std::pair<double, int>> runs;  // the default effort first: the others' ratios read it
    for (double tol : {1e-2, 1e-3, 1e-4}) runs.emplace_back(tol, standard);
    for (int effort = standard - 1; effort >= 1; --effort) runs.emplace_back(1e-3, effort);
    for (const auto& [tol, effort] : runs) {
      std::string label = "encode/" + name + "/tol=" + std::to_string(tol);
      if (effort != standard) label += "/effort=" + std::to_string(effort);
      benchmark::RegisterBenchmark(label.c_str(),
                                   [name, tol = tol, effort = effort](benchmark::State& s) { BM_Encode(s, name, tol, effort); })
          ->Unit(benchmark::kSecond)
          ->Iterations(1)
          ->UseRealTime();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  register_all();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
