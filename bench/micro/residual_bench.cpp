// Residual layer on corpus-ext: coded bytes against quantized temporal delta (varint +
// zstd -19, the thin path) on the same grid values, the same residuals through zstd
// instead of the range coder, the same residuals through Debian's htscodecs (rANS 4x16 and
// adaptive arithmetic, order 0 and 1; when installed), and load (decode) speed. Sequences come from
// DCURVE_CORPUS_EXT (environment) or ../shared/corpus-ext; tolerances from
// DCURVE_RESIDUAL_TOLS (comma list, default "1e-3").
#include <benchmark/benchmark.h>
#include <zstd.h>
#ifdef DCURVE_HAVE_HTSCODECS
#include <htscodecs/arith_dynamic.h>
#include <htscodecs/rANS_static4x16.h>
#endif

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>

#include "codec/common/bytes.h"
#include "codec/common/residual.h"
#include "codec/compress/residual_values.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/residual_decoder.h"
#include "encoder/encoder.h"
#include "encoder/rate/residual_plan.h"

namespace {
using namespace dcurve;

struct Case {
  Model model;  // as read back from the encoded file
  std::vector<int32_t> q;
  size_t delta_zstd = 0, plan_zstd = 0;
  // The same residual bytes through htscodecs: rANS order 0, 1, arithmetic order 0, 1.
  size_t plan_hts[4] = {0, 0, 0, 0};
};


size_t zstd_size(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> out(ZSTD_compressBound(raw.size()));
  return ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 19);
}

// Zigzag varints: one byte per residual below 64 in magnitude, which is nearly all of them.
std::vector<uint8_t> varint_bytes(const std::vector<int64_t>& values) {
  ByteWriter w;
  for (int64_t v : values) w.varint(zigzag_encode(v));
  return w.data();
}

size_t varint_zstd(const std::vector<int64_t>& values) { return zstd_size(varint_bytes(values)); }

#ifdef DCURVE_HAVE_HTSCODECS
// Compressed sizes of `raw` with rANS 4x16 order 0 and 1 and adaptive arithmetic order 0
// and 1; 0 where a codec fails.
void hts_sizes(std::vector<uint8_t> raw, size_t out[4]) {
  for (int k = 0; k < 4; ++k) {
    unsigned int size = 0;
    unsigned char* packed = k < 2 ? rans_compress_4x16(raw.data(), unsigned(raw.size()), &size, k)
                                  : arith_compress(raw.data(), unsigned(raw.size()), &size, k - 2);
    out[k] = packed ? size : 0;
    std::free(packed);
  }
}
#endif

std::string corpus() {
  const char* env = std::getenv("DCURVE_CORPUS_EXT");
  return env ? env : "../shared/corpus-ext";
}

const Case* load(const std::string& seq, double tol) {
  static std::map<std::pair<std::string, double>, Case> cache;
  auto key = std::make_pair(seq, tol);
  auto it = cache.find(key);
  if (it != cache.end()) return &it->second;
  Animation anim;
  std::string err;
  if (!read_frame_folder(corpus() + "/" + seq, &anim, &err)) return nullptr;
  EncodeOptions eo;
  eo.tolerance = tol;
  std::vector<uint8_t> file;
  if (!encode_animation(anim, eo, &file, nullptr, &err)) return nullptr;
  Case c;
  if (!read_container(file.data(), file.size(), &c.model, &err) || !decode_residuals(c.model, &c.q, &err))
    return nullptr;
  const size_t n = size_t(c.model.meta.vertex_count) * 3;
  // The thin path's values: every position rounded to the nearest grid point.
  std::vector<int64_t> rounded(c.q.size()), delta(c.q.size());
  const ResidualLayer& layer = c.model.residual;
  for (size_t i = 0; i < c.q.size(); ++i)
    rounded[i] = int64_t(std::nearbyint((double(anim.frames[i / n][i % n]) - layer.origin[i % 3]) / layer.step));
  for (size_t i = 0; i < c.q.size(); ++i) delta[i] = rounded[i] - (i >= n ? rounded[i - n] : 0);
  c.delta_zstd = varint_zstd(delta);
  ResidualPlan plan;
  if (!decode_predictor_plan(c.model, &plan, &err, {}, true)) return nullptr;
  const std::vector<int64_t> residuals = residual_values(c.model, c.q, plan);
  c.plan_zstd = varint_zstd(residuals);
#ifdef DCURVE_HAVE_HTSCODECS
  hts_sizes(varint_bytes(residuals), c.plan_hts);
#endif
  return &cache.emplace(key, std::move(c)).first->second;
}

void BM_ResidualLoad(benchmark::State& state, std::string seq, double tol) {
  const Case* c = load(seq, tol);
  if (!c) {
    state.SkipWithError(("cannot read or encode " + corpus() + "/" + seq).c_str());
    return;
  }
  std::vector<int32_t> q;
  std::string err;
  for (auto _ : state) {
    if (!decode_residuals(c->model, &q, &err)) state.SkipWithError(err.c_str());
    benchmark::DoNotOptimize(q.data());
  }
  const double payload = double(c->model.residual.payload.size());
  const double vf = double(c->model.meta.vertex_count) * c->model.meta.frame_count;
  state.counters["bytes"] = payload;
  state.counters["delta_zstd_bytes"] = double(c->delta_zstd);
  state.counters["ratio_vs_delta"] = payload / double(c->delta_zstd);
  state.counters["same_residuals_zstd_bytes"] = double(c->plan_zstd);
#ifdef DCURVE_HAVE_HTSCODECS
  const char* hts_names[4] = {"same_rans0_bytes", "same_rans1_bytes", "same_arith0_bytes", "same_arith1_bytes"};
  for (int k = 0; k < 4; ++k) state.counters[hts_names[k]] = double(c->plan_hts[k]);
#endif
  state.counters["bpvf"] = 8 * payload / vf;
  state.counters["delta_bpvf"] = 8 * double(c->delta_zstd) / vf;
  state.counters["out_MBps"] = benchmark::Counter(4.0 * double(c->q.size()) / 1e6,
                                                   benchmark::Counter::kIsIterationInvariantRate);
}

int register_all() {
  const char* env = std::getenv("DCURVE_RESIDUAL_TOLS");
  std::string tols = env ? env : "1e-3";
  for (size_t p = 0; p < tols.size();) {
    size_t q = tols.find(',', p);
    const double tol = std::atof(tols.substr(p, q - p).c_str());
    for (const char* seq : {"horse-gallop", "chicken-crossing", "cloth-sphere", "elastic-cow", "crane"})
      benchmark::RegisterBenchmark((std::string("ResidualLoad/") + seq + "/" + tols.substr(p, q - p)).c_str(),
                                   BM_ResidualLoad, std::string(seq), tol)
          ->Unit(benchmark::kMillisecond);
    p = q == std::string::npos ? tols.size() : q + 1;
  }
  return 0;
}
const int registered = register_all();

}  // namespace

BENCHMARK_MAIN();
