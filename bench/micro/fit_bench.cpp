// Fit speed: curves per second for the 8-term and 32-term fits on 1 and 2 threads, plus one
// pair of 71-point curves (the 2022 paper's Table 2 case: 5.75 ms) and the polynomial
// least-squares fit of the same size as the in-run baseline.
//
// Data: rows of corpus-ext/cloth-sphere (50 points each; frames 40..50, the draping) when the
// corpus is present, else a synthetic sheet with the same sizes. Reference: the 2022 paper
// reconstructs its 593-curve horse in 1827 ms (about 325 curves/s, two keyframes).
#include <benchmark/benchmark.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>

#include "bench/paper_protocols.h"
#include "encoder/fit/curve_frames.h"
#include "encoder/fit/fit.h"

#include <cstdio>
#include <cstdlib>

namespace dcurve {
namespace {

// cloth-sphere (or the synthetic stand-in), loaded once.
const Animation& cloth() {
  static Animation anim;
  static bool loaded = false;
  if (!loaded) {
    std::string error;
    // The corpus folder comes from the environment (DCURVE_CORPUS_EXT), else ../shared beside the build.
    const char* env = std::getenv("DCURVE_CORPUS_EXT");
    std::string dir = std::string(env ? env : "../shared/corpus-ext") + "/cloth-sphere";
    if (!std::filesystem::exists(dir) || !read_frame_folder(dir, &anim, &error)) {
      anim = Animation();
      anim.vertex_count = 2500;
      for (int f = 0; f < 60; ++f) {
        std::vector<float> xyz;
        for (int r = 0; r < 50; ++r)
          for (int c = 0; c < 50; ++c) {
            double u = c / 49.0, v = r / 49.0, t = f / 59.0;
            xyz.insert(xyz.end(), {float(u), float(v + 0.1 * std::sin(4 * u + t)), float(0.3 * std::cos(5 * u * v + 2 * t))});
          }
        anim.frames.push_back(xyz);
      }
    }
    loaded = true;
  }
  return anim;
}

Curves cloth_rows() {
  Curves curves;
  std::string error;
  grid_row_curves(cloth(), 50, &curves, &error);
  return curves;
}

// 50 rows of 50 points, at `frames` frames spread over frames 40..50 of cloth-sphere.
std::vector<CurveFrames> load_curves(uint32_t frames) {
  const Animation& anim = cloth();
  Curves curves = cloth_rows();
  std::vector<uint32_t> ids;
  std::vector<double> tau;
  for (uint32_t k = 0; k < frames; ++k) {
    ids.push_back(40 + (frames > 1 ? k * 10 / (frames - 1) : 0));
    tau.push_back(frames > 1 ? double(k) / (frames - 1) : 0.0);
  }
  std::vector<CurveFrames> out;
  for (uint32_t c = 0; c < curves.curve_count(); ++c) out.push_back(gather_curve_frames(anim, curves, c, ids, tau));
  return out;
}

// args: basis (1 = Pde8, 2 = Pde32), threads
void BM_FitCurves(benchmark::State& state) {
  const Basis basis = Basis(state.range(0));
  const int threads = int(state.range(1));
  std::vector<CurveFrames> curves = load_curves(basis == Basis::Pde8 ? 2 : 6);
  FitOptions options;
  options.basis = basis;
  options.remove_rigid = basis == Basis::Pde32;
  std::vector<CurveFit> fits;
  std::string error;
  for (auto _ : state) {
    if (!fit_curves(curves, options, threads, &fits, &error)) state.SkipWithError(error.c_str());
    benchmark::DoNotOptimize(fits.data());
  }
  state.SetItemsProcessed(int64_t(state.iterations()) * int64_t(curves.size()));
  state.counters["curves_per_s"] = benchmark::Counter(double(state.iterations()) * double(curves.size()),
                                                      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FitCurves)->ArgNames({"basis", "threads"})->Args({1, 1})->Args({1, 2})->Args({2, 1})->Args({2, 2})
    ->Unit(benchmark::kMillisecond)->UseRealTime();

// Two 71-point curves (one per keyframe), the 2022 paper's Table 2 case.
CurveFrames pair_of_71_point_curves() {
  CurveFrames c;
  for (int p = 0; p < 71; ++p) c.u.push_back(p / 70.0);
  c.tau = {0.0, 1.0};
  for (int f = 0; f < 2; ++f)
    for (int p = 0; p < 71; ++p) {
      double u = p / 70.0;
      c.xyz.insert(c.xyz.end(), {std::cos(6.2 * u) * (1 + 0.2 * f), std::sin(6.2 * u) + 0.3 * u * f, 0.5 * u * u});
    }
  return c;
}

void BM_FitPde8Pair71(benchmark::State& state) {
  CurveFrames c = pair_of_71_point_curves();
  FitOptions options;
  CurveFit fit;
  std::string error;
  for (auto _ : state) {
    fit_curve(c, options, &fit, &error);
    benchmark::DoNotOptimize(fit.rms_error);
  }
}
BENCHMARK(BM_FitPde8Pair71)->Unit(benchmark::kMillisecond);

// Baseline in the same run: the "cubic in u x linear in t" least-squares fit of the same pair
// (8 coefficients per axis, one QR): what the parameter search costs on top.
void BM_PolynomialPair71(benchmark::State& state) {
  CurveFrames c = pair_of_71_point_curves();
  const Eigen::Index n = Eigen::Index(c.points() * c.frames());
  for (auto _ : state) {
    Eigen::MatrixXd a(n, 8), y(n, 3);
    for (size_t f = 0; f < c.frames(); ++f)
      for (size_t p = 0; p < c.points(); ++p) {
        Eigen::Index row = Eigen::Index(f * c.points() + p);
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 4; ++j) a(row, i * 4 + j) = std::pow(c.tau[f], i) * std::pow(c.u[p], j);
        for (int k = 0; k < 3; ++k) y(row, k) = c.xyz[size_t(row) * 3 + size_t(k)];
      }
    Eigen::MatrixXd coeffs = a.colPivHouseholderQr().solve(y);
    benchmark::DoNotOptimize(coeffs.data());
  }
}
BENCHMARK(BM_PolynomialPair71)->Unit(benchmark::kMillisecond);

// The papers' protocols on all 50 cloth rows (2024: frames 40..50 as 0..10, the draping;
// 2022: keyframes 20 and 100). Prints the tables once; the counters repeat the summaries.
void BM_PaperProtocol(benchmark::State& state) {
  const bool is2024 = state.range(0) == 2024;
  Animation anim = cloth();
  if (is2024) anim.frames.assign(cloth().frames.begin() + 40, cloth().frames.begin() + 51);
  Curves curves = cloth_rows();
  nlohmann::json j;
  std::string table, error;
  bool printed = false;
  for (auto _ : state) {
    if (!run_paper_protocol(is2024 ? "paper2024" : "paper2022", anim, curves, &j, &table, &error)) {
      state.SkipWithError(error.c_str());
      return;
    }
    if (!printed) std::printf("%s", table.c_str());
    printed = true;
  }
  state.counters["pde_mean_EA"] = j["pde"]["mean_EA"].get<double>();
  state.counters["pde_max_EM"] = j["pde"]["max_EM"].get<double>();
  const char* other = is2024 ? "bspline" : "bezier";
  state.counters[std::string(other) + "_mean_EA"] = j[other]["mean_EA"].get<double>();
  state.counters[std::string(other) + "_max_EM"] = j[other]["max_EM"].get<double>();
}
BENCHMARK(BM_PaperProtocol)->Arg(2024)->Arg(2022)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace dcurve

BENCHMARK_MAIN();
