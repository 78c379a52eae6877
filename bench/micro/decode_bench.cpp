// Runtime decode speed on a real sequence, in one run: dcurve's evaluate at random t (frames
// only, and with PDE models on every curve), a memcpy of a frame's positions (the limit) and
// Draco's decode of the same frame; then the ratios (DESIGN.md sec. 7 goals: <= 3x memcpy,
// >= 50x faster than Draco). Also prints FACE coder sizes on every corpus sequence.
//
//   DCURVE_CORPUS_EXT=/path/to/corpus-ext [DCURVE_BENCH_SEQUENCE=horse-gallop] build/bench/decode_bench
#include <benchmark/benchmark.h>
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <zstd.h>
#ifdef DCURVE_HAVE_MESHOPT
#include <meshoptimizer.h>
#endif

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>

#include "bench/draco_frame.h"
#include "codec/common/basis.h"
#include "codec/common/bytes.h"
#include "codec/common/faces.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/faces_encoder.h"
#include "codec/compress/quantize.h"
#include "codec/decompress/container_reader.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/io/frames.h"

namespace {
using namespace dcurve;

std::string corpus_dir() {
  const char* env = std::getenv("DCURVE_CORPUS_EXT");
  return env ? env : "";
}

struct Fixture {
  Animation anim;
  std::vector<uint8_t> frames_file, pde8_file;
  std::unique_ptr<Decoder> frames_only, pde8_c16, pde8_c64, pde32_c64, pde8_c64_shared;
  std::vector<std::vector<uint8_t>> draco_frames;
  std::vector<double> times;  // random t in [0, 1]
  std::string name;
};

// The thin encoder's file plus curves of `curve_len` consecutive vertex ids and 8-frame
// segments whose motions all use `basis` with their own random parameters on both sides of
// the switch value: a worst case for evaluation cost (every curve and axis carries a model;
// a rate-controlled file drops the models that do not pay). Output at the frames is
// unchanged (the corrections absorb the model); only speed is measured.
// With shared_time_param every motion of a segment has the same mu (as with the fit's
// fixed_time_param option), so the decoder computes the time functions once per segment.
std::vector<uint8_t> with_models(const std::vector<uint8_t>& file, Basis basis, uint32_t curve_len,
                                 bool shared_time_param = false) {
  Model m;
  std::string err;
  read_container(file.data(), file.size(), &m, &err);
  const uint32_t V = m.meta.vertex_count, F = m.meta.frame_count;
  m.curves = Curves{};
  for (uint32_t v = 0; v < V; ++v) {
    if (v % curve_len == 0) m.curves.offsets.push_back(v);
    m.curves.vertices.push_back(v);
    m.curves.u.push_back(quantize_curve_u(float(v % curve_len) / float(curve_len - 1)));
  }
  m.curves.offsets.push_back(V);
  m.curves.closed.assign(m.curves.offsets.size() - 1, 0);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> coeff(-1e-3f, 1e-3f), param(0.5f, 12.f);
  for (uint32_t first = 0; first + 1 < F || m.segments.empty(); first += 8) {
    Segment s;
    s.first_frame = first;
    s.last_frame = std::min(first + 8, F - 1);
    s.motion.resize(size_t(m.curves.curve_count()) * 3);
    const float segment_mu = param(rng);
    for (CurveMotion& cm : s.motion) {
      cm.basis = basis;
      cm.basis_case = basis == Basis::Pde8 ? uint8_t(shared_time_param ? 0 : rng() % 4) : 0;
      cm.time_param = shared_time_param ? segment_mu : param(rng);
      cm.space_param = param(rng);
      cm.coeffs.resize(size_t(basis_term_count(basis)));
      for (float& c : cm.coeffs) c = coeff(rng);
    }
    m.segments.push_back(s);
    if (s.last_frame == F - 1) break;
  }
  return write_container(m);
}

std::vector<uint8_t> draco_encode(const Animation& a, const std::vector<float>& xyz) {
  draco::Mesh mesh;
  mesh.set_num_points(a.vertex_count);
  draco::GeometryAttribute ga;
  ga.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, sizeof(float) * 3, 0);
  int id = mesh.AddAttribute(ga, true, a.vertex_count);
  for (uint32_t v = 0; v < a.vertex_count; ++v)
    mesh.attribute(id)->SetAttributeValue(draco::AttributeValueIndex(v), &xyz[3 * v]);
  for (size_t t = 0; t + 2 < a.faces.size(); t += 3)
    mesh.AddFace({draco::PointIndex(a.faces[t]), draco::PointIndex(a.faces[t + 1]), draco::PointIndex(a.faces[t + 2])});
  draco::Encoder enc;
  enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
  draco::EncoderBuffer buf;
  if (!enc.EncodeMeshToBuffer(mesh, &buf).ok()) return {};
  return std::vector<uint8_t>(buf.data(), buf.data() + buf.size());
}

Fixture* fixture() {
  static Fixture* f = [] {
    auto* fx = new Fixture;
    const char* seq = std::getenv("DCURVE_BENCH_SEQUENCE");
    fx->name = seq ? seq : "horse-gallop";
    std::string err;
    if (!read_frame_folder(corpus_dir() + "/" + fx->name, &fx->anim, &err)) {
      std::fprintf(stderr, "decode_bench: %s (set DCURVE_CORPUS_EXT)\n", err.c_str());
      std::exit(1);
    }
    EncodeReport rep;
    if (!encode_animation(fx->anim, EncodeOptions{}, &fx->frames_file, &rep, &err)) {
      std::fprintf(stderr, "decode_bench: encode failed: %s\n", err.c_str());
      std::exit(1);
    }
    fx->frames_only = Decoder::open_memory(fx->frames_file.data(), fx->frames_file.size(), &err);
    auto open_with = [&](Basis b, uint32_t len, bool shared = false) {
      std::vector<uint8_t> file = with_models(fx->frames_file, b, len, shared);
      if (b == Basis::Pde8 && len == 16) fx->pde8_file = file;
      return Decoder::open_memory(file.data(), file.size(), &err);
    };
    fx->pde8_c16 = open_with(Basis::Pde8, 16);
    fx->pde8_c64 = open_with(Basis::Pde8, 64);
    fx->pde32_c64 = open_with(Basis::Pde32, 64);
    fx->pde8_c64_shared = open_with(Basis::Pde8, 64, true);
    if (!fx->frames_only || !fx->pde8_c16 || !fx->pde8_c64 || !fx->pde32_c64 || !fx->pde8_c64_shared) {
      std::fprintf(stderr, "decode_bench: decode failed: %s\n", err.c_str());
      std::exit(1);
    }
    for (size_t f = 0; f < fx->anim.frames.size(); f += 6) fx->draco_frames.push_back(draco_encode(fx->anim, fx->anim.frames[f]));
    std::mt19937 rng(42);
    std::uniform_real_distribution<double> u01(0, 1);
    for (int i = 0; i < 4096; ++i) fx->times.push_back(u01(rng));
    return fx;
  }();
  return f;
}

void report_vertices(benchmark::State& state) {
  state.counters["vertices_per_s"] =
      benchmark::Counter(double(state.iterations()) * fixture()->anim.vertex_count, benchmark::Counter::kIsRate);
}

void BM_Memcpy(benchmark::State& state) {
  Fixture* fx = fixture();
  std::vector<float> out(size_t(fx->anim.vertex_count) * 3);
  size_t k = 0;
  for (auto _ : state) {
    const auto& src = fx->anim.frames[k++ % fx->anim.frames.size()];
    std::memcpy(out.data(), src.data(), src.size() * sizeof(float));
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  report_vertices(state);
}

void evaluate_bench(benchmark::State& state, const Decoder& d) {
  Fixture* fx = fixture();
  std::vector<float> out(size_t(fx->anim.vertex_count) * 3);
  size_t k = 0;
  for (auto _ : state) {
    d.evaluate(fx->times[k++ % fx->times.size()], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  report_vertices(state);
}
void BM_DcrvEvaluateFrames(benchmark::State& s) { evaluate_bench(s, *fixture()->frames_only); }
void BM_DcrvEvaluatePde8Curve16(benchmark::State& s) { evaluate_bench(s, *fixture()->pde8_c16); }
void BM_DcrvEvaluatePde8Curve64(benchmark::State& s) { evaluate_bench(s, *fixture()->pde8_c64); }
void BM_DcrvEvaluatePde32Curve64(benchmark::State& s) { evaluate_bench(s, *fixture()->pde32_c64); }
void BM_DcrvEvaluatePde8Curve64SharedMu(benchmark::State& s) { evaluate_bench(s, *fixture()->pde8_c64_shared); }

void BM_DracoDecode(benchmark::State& state) {
  Fixture* fx = fixture();
  size_t k = 0;
  for (auto _ : state) {
    const auto& bytes = fx->draco_frames[k++ % fx->draco_frames.size()];
    draco::DecoderBuffer buf;
    buf.Init(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    draco::Decoder dec;
    auto mesh = dec.DecodeMeshFromBuffer(&buf);
    if (!mesh.ok()) state.SkipWithError("draco decode failed");
    benchmark::DoNotOptimize(mesh.value().get());
  }
  report_vertices(state);
}

void BM_DcrvOpen(benchmark::State& state) {
  Fixture* fx = fixture();
  std::string err;
  for (auto _ : state) benchmark::DoNotOptimize(Decoder::open_memory(fx->pde8_file.data(), fx->pde8_file.size(), &err));
}

BENCHMARK(BM_Memcpy);
BENCHMARK(BM_DcrvEvaluateFrames);
BENCHMARK(BM_DcrvEvaluatePde8Curve16);
BENCHMARK(BM_DcrvEvaluatePde8Curve64);
BENCHMARK(BM_DcrvEvaluatePde32Curve64);
BENCHMARK(BM_DcrvEvaluatePde8Curve64SharedMu);
BENCHMARK(BM_DracoDecode);
BENCHMARK(BM_DcrvOpen)->Unit(benchmark::kMillisecond);

// Keeps each benchmark's CPU time per iteration so the ratios can be printed after the run
// (CPU, not wall time: the machine is shared and every benchmark here is single-threaded).
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  std::map<std::string, double> seconds;
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) seconds[r.benchmark_name()] = r.GetAdjustedCPUTime();
    ConsoleReporter::ReportRuns(runs);
  }
};

size_t zstd_size(const std::vector<uint8_t>& raw) {
  std::vector<uint8_t> out(ZSTD_compressBound(raw.size()));
  return ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), 19);
}

size_t stored_size(const std::vector<uint8_t>& raw) { return std::min(raw.size(), zstd_size(raw)); }

// Connectivity options, bytes per triangle after zstd -19 (the container's compression).
void print_face_sizes() {
  std::printf("FACE coder, bytes per triangle (zstd -19), corpus-ext frame 0:\n");
  std::printf("(exact: FACE layout 0 on the input order; trav: layout 1; compact: layout 2 on the traversal\n"
              " order; exact/trav-order: layout 0 on the traversal order; meshopt: meshopt_encodeIndexBuffer,\n"
              " which rotates corners; draco-eb: Draco edgebreaker with all positions at the origin, which\n"
              " also renumbers vertices)\n");
  std::printf("%-18s %8s %9s %11s %11s %10s %8s %17s %13s %9s\n", "sequence", "tris", "raw+zstd", "delta+zstd",
              "exact+zstd", "trav+zstd", "compact", "exact/trav-order", "meshopt+zstd", "draco-eb");
  std::string bytes_table;
  for (const char* seq : {"horse-gallop", "chicken-crossing", "elastic-cow", "cloth-sphere", "crane"}) {
    Animation a;
    std::vector<float> xyz;
    std::string err;
    if (!read_mesh(corpus_dir() + "/" + seq + "/frame_00000.obj", &xyz, &a.faces, &err)) continue;
    a.vertex_count = uint32_t(xyz.size() / 3);
    const double T = double(a.faces.size() / 3);
    std::vector<uint8_t> raw(reinterpret_cast<const uint8_t*>(a.faces.data()),
                             reinterpret_cast<const uint8_t*>(a.faces.data() + a.faces.size()));
    ByteWriter delta;  // container v0's coder: index deltas as zigzag varints
    int64_t prev = 0;
    for (uint32_t i : a.faces) {
      delta.varint(zigzag_encode(int64_t(i) - prev));
      prev = i;
    }
    double meshopt = -1;
#ifdef DCURVE_HAVE_MESHOPT
    std::vector<uint8_t> mo(meshopt_encodeIndexBufferBound(a.faces.size(), a.vertex_count));
    mo.resize(meshopt_encodeIndexBuffer(mo.data(), mo.size(), a.faces.data(), a.faces.size()));
    meshopt = zstd_size(mo) / T;
#endif
    // Draco edgebreaker with every position at the origin: what is left is connectivity.
    std::vector<float> zeros(xyz.size(), 0.f);
    const size_t draco = draco_encode(a, zeros).size();
    const std::vector<uint32_t> trav = traversal_order(a.faces);
    const size_t exact = stored_size(encode_faces(a.faces, FaceOrder::Exact));
    const size_t traversal = stored_size(encode_faces(trav, FaceOrder::Traversal));
    const size_t compact = stored_size(encode_faces(trav, FaceOrder::Compact));
    const size_t compact_input = stored_size(encode_faces(a.faces, FaceOrder::Compact));
    std::printf("%-18s %8.0f %9.3f %11.3f %11.3f %10.3f %8.3f %17.3f %13.3f %9.3f\n", seq, T, zstd_size(raw) / T,
                zstd_size(delta.data()) / T, exact / T, traversal / T, compact / T,
                zstd_size(encode_faces(trav, FaceOrder::Exact)) / T, meshopt, draco / T);
    char line[256];
    // What `dcurve bench` charges for connectivity: Draco at compression level 10.
    bench::DracoFrameCodec level10;
    const bool have_level10 = level10.init(a.vertex_count, a.faces, &err);
    std::snprintf(line, sizeof line, "| %s | %.0f | %zu | %zu | %zu | %zu | %zu | %lld |\n", seq, T, exact, traversal,
                  compact, compact_input, draco, have_level10 ? (long long)level10.connectivity_bytes() : -1LL);
    bytes_table += line;
  }
  std::printf("\nFACE payload bytes (stored: zstd -19 when smaller), Markdown:\n"
              "| sequence | triangles | layout 0, input order | layout 1 | layout 2, traversal order |"
              " layout 2, input order | Draco, default speed | Draco, level 10 (bench conn.B) |\n|---|---|---|---|---|---|---|---|\n%s",
              bytes_table.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (corpus_dir().empty()) {
    std::fprintf(stderr, "decode_bench: set DCURVE_CORPUS_EXT to the corpus-ext folder\n");
    return 1;
  }
  Fixture* fx = fixture();
  std::printf("sequence %s: %u vertices, %zu frames; frames-only file %zu B\n", fx->name.c_str(),
              fx->anim.vertex_count, fx->anim.frames.size(), fx->frames_file.size());
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  auto& s = reporter.seconds;
  if (s.count("BM_Memcpy") && s.count("BM_DracoDecode")) {
    std::printf("\nratios (same run):\n");
    for (const char* b : {"BM_DcrvEvaluateFrames", "BM_DcrvEvaluatePde8Curve16", "BM_DcrvEvaluatePde8Curve64",
                          "BM_DcrvEvaluatePde32Curve64", "BM_DcrvEvaluatePde8Curve64SharedMu"}) {
      if (!s.count(b)) continue;
      std::printf("  %-34s %6.2fx memcpy (goal <= 3),  Draco decode / this = %7.1fx (goal >= 50)\n", b,
                  s[b] / s["BM_Memcpy"], s["BM_DracoDecode"] / s[b]);
    }
  }
  print_face_sizes();
  benchmark::Shutdown();
  return 0;
}
