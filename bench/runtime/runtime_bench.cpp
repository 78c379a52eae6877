// What a game pays to play a .dcrv (DESIGN.md section 7), measured through the real decode
// in one run per file: open time; open plus the middle frame from a fresh open (random
// access); open plus every frame in order through a cursor (sequential playback, in
// vertex-frames per second) and from it the steady time per frame; a seek (a fresh cursor on
// an open decoder, one middle frame) against that frame time; the memory the decoder and
// cursor hold after playback against the raw float32 size. Beside them, in the same process: libdraco decoding the same frames
// (each decoded frame written by Draco at the smallest quantization that meets the file's
// tolerance, as `dcurve bench` does), quantized delta + zstd decoding them (the strongest
// simple baseline, DESIGN.md section 6) and a memcpy of them (the limit).
//
//   build/bench/runtime_bench FILE.dcrv...
//   scripts/runtime-bench.sh: horse-gallop and a 600-frame rope-small clip, encoded first
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "bench/baselines.h"
#include "bench/draco_per_frame.h"
#include "decoder/dcurve.hpp"
#include "encoder/io/files.h"

namespace {
using namespace dcurve;
using Clock = std::chrono::steady_clock;

// Runs of each figure, whose median is printed: the playback and Draco figures once took 3,
// and their ratio moved by a fifth between runs on this shared machine.
constexpr int kRuns = 9;

// Median seconds of `runs` calls of `work`.
double median_seconds(int runs, const std::function<bool()>& work) {
  std::vector<double> t;
  for (int i = 0; i < runs; ++i) {
    const auto start = Clock::now();
    if (!work()) return -1;
    t.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct Figures {
  uint32_t vertices = 0, frames = 0, chunk_frames = 0;
  uint64_t file_bytes = 0, raw_bytes = 0, memory_bytes = 0;
  double open_s = 0, middle_s = 0, playback_s = 0, seek_s = 0, draco_s = -1, memcpy_s = 0, delta_s = -1;
  int draco_bits = 0;
};

// Opens `bytes` and evaluates frames [first, last] in order through one cursor.
bool play(const std::vector<uint8_t>& bytes, uint32_t first, uint32_t last, std::vector<float>* xyz,
          size_t* memory = nullptr) {
  std::string err;
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  if (!dec) return false;
  auto cursor = dec->make_cursor();
  for (uint32_t f = first; f <= last; ++f)
    if (!cursor->evaluate_frame(f, xyz->data())) return false;
  if (memory) *memory = dec->memory_bytes() + cursor->memory_bytes();
  return true;
}

// A fresh cursor on the open decoder `dec`, evaluating frame f alone.
bool seek(const Decoder& dec, uint32_t f, std::vector<float>* xyz) {
  auto cursor = dec.make_cursor();
  return cursor && cursor->evaluate_frame(f, xyz->data());
}

// The decoded frames as an animation Draco can take (the decoder's faces).
bool decoded_animation(const std::vector<uint8_t>& bytes, Animation* anim, double* tolerance, double* diagonal,
                       std::string* error) {
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), error);
  if (!dec) return false;
  anim->vertex_count = dec->vertex_count();
  anim->faces.assign(dec->faces(), dec->faces() + size_t(dec->face_count()) * 3);
  anim->frames.assign(dec->frame_count(), std::vector<float>(size_t(dec->vertex_count()) * 3));
  for (uint32_t f = 0; f < dec->frame_count(); ++f)
    if (!dec->evaluate_frame(f, anim->frames[f].data(), nullptr)) return false;
  *tolerance = dec->tolerance();
  *diagonal = dec->rest_diagonal();
  return true;
}

// libdraco's decode of every frame, each at its smallest sufficient quantization.
void measure_draco(const Animation& anim, double tolerance, double diagonal, Figures* out) {
  bench::DracoFrameCodec codec;
  std::string err;
  if (anim.faces.empty() || !codec.init(anim.vertex_count, anim.faces, &err)) {
    std::fprintf(stderr, "runtime_bench: Draco skipped: %s\n", anim.faces.empty() ? "no faces" : err.c_str());
    return;
  }
  const bench::BenchContext ctx{anim, tolerance, diagonal, codec, 0, 1};
  bench::DracoPerFrameChoice choice;
  if (!bench::choose_draco_per_frame(ctx, &choice, &err)) {
    std::fprintf(stderr, "runtime_bench: Draco skipped: %s\n", err.c_str());
    return;
  }
  out->draco_bits = *std::max_element(choice.bits.begin(), choice.bits.end());
  std::vector<float> xyz(size_t(anim.vertex_count) * 3);
  out->draco_s = median_seconds(kRuns, [&] {
    for (const std::vector<char>& file : choice.files)
      if (!codec.decode(file, &xyz, nullptr, false)) return false;
    return true;
  });
}

// The quantized delta + zstd baseline (bench/quantized_delta.cpp) decoding the same frames:
// the whole clip unpacked and every frame dequantized, best of up to three runs.
void measure_quantized_delta(const Animation& anim, double tolerance, double diagonal, Figures* out) {
  bench::DracoFrameCodec unused;  // the baseline codes no connectivity
  const bench::BenchContext ctx{anim, tolerance, diagonal, unused, 0, 1};
  bench::MethodResult r;
  std::string err;
  if (!bench::bench_quantized_delta(ctx, &r, &err) || r.decode_vertices_per_second <= 0) {
    std::fprintf(stderr, "runtime_bench: quantized delta skipped: %s\n", err.c_str());
    return;
  }
  out->delta_s = double(anim.vertex_count) * double(anim.frames.size()) / r.decode_vertices_per_second;
}

bool measure(const std::string& path, Figures* out) {
  std::vector<uint8_t> bytes;
  std::string err;
  Animation anim;
  double tolerance = 0, diagonal = 0;
  if (!read_file(path, &bytes, &err) || !decoded_animation(bytes, &anim, &tolerance, &diagonal, &err)) {
    std::fprintf(stderr, "runtime_bench: %s: %s\n", path.c_str(), err.c_str());
    return false;
  }
  Figures& f = *out;
  f.vertices = anim.vertex_count;
  f.frames = uint32_t(anim.frames.size());
  f.file_bytes = bytes.size();
  f.raw_bytes = uint64_t(12) * f.vertices * f.frames;
  std::vector<float> xyz(size_t(f.vertices) * 3);
  f.open_s = median_seconds(kRuns, [&] { return Decoder::open_memory(bytes.data(), bytes.size(), &err) != nullptr; });
  f.middle_s = median_seconds(kRuns, [&] { return play(bytes, f.frames / 2, f.frames / 2, &xyz); });
  f.playback_s = median_seconds(kRuns, [&] { return play(bytes, 0, f.frames - 1, &xyz, &f.memory_bytes); });
  f.memcpy_s = median_seconds(kRuns, [&] {
    for (const std::vector<float>& frame : anim.frames) std::memcpy(xyz.data(), frame.data(), frame.size() * 4);
    return xyz[0] == anim.frames.back()[0];
  });
  auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  f.chunk_frames = dec ? dec->chunk_frames() : 0;
  if (dec) f.seek_s = median_seconds(kRuns, [&] { return seek(*dec, f.frames / 2, &xyz); });
  measure_draco(anim, tolerance, diagonal, &f);
  measure_quantized_delta(anim, tolerance, diagonal, &f);
  return true;
}

void print(const std::string& path, const Figures& f) {
  const double vf = double(f.vertices) * f.frames;
  std::printf("%s: %u vertices x %u frames, %llu bytes, chunks of %u frames\n", path.c_str(), f.vertices, f.frames,
              (unsigned long long)f.file_bytes, f.chunk_frames);
  std::printf("  open                     %10.3f ms\n", 1e3 * f.open_s);
  std::printf("  open + middle frame      %10.3f ms  = %.3f of open + every frame\n", 1e3 * f.middle_s,
              f.middle_s / f.playback_s);
  std::printf("  open + every frame       %10.3f ms  = %.2f M vertex-frames/s\n", 1e3 * f.playback_s,
              vf / f.playback_s / 1e6);
  const double frame_s = std::max(f.playback_s - f.open_s, 0.0) / f.frames;
  std::printf("  steady frame             %10.4f ms  (open + every frame, less the open, per frame)\n", 1e3 * frame_s);
  std::printf("  seek                     %10.4f ms  = %.2f steady frames (fresh cursor, open decoder, middle frame; goal <= 4)\n",
              1e3 * f.seek_s, frame_s > 0 ? f.seek_s / frame_s : 0.0);
  if (f.draco_s > 0)
    std::printf("  Draco, same frames       %10.3f ms  = %.2f M vertex-frames/s (%d bits); dcurve %.2fx Draco (goal >= 10)\n",
                1e3 * f.draco_s, vf / f.draco_s / 1e6, f.draco_bits, f.draco_s / f.playback_s);
  if (f.delta_s > 0)
    std::printf("  quantized delta + zstd   %10.3f ms  = %.2f M vertex-frames/s; dcurve %.2fx its rate (goal >= 0.5)\n",
                1e3 * f.delta_s, vf / f.delta_s / 1e6, f.delta_s / f.playback_s);
  std::printf("  memcpy, same frames      %10.3f ms  = %.2f M vertex-frames/s; dcurve %.1fx slower\n", 1e3 * f.memcpy_s,
              vf / f.memcpy_s / 1e6, f.playback_s / f.memcpy_s);
  std::printf("  memory after playback    %10llu bytes = %.3f of raw float32 (%llu bytes; goal <= 0.5 for horse-gallop, "
              "0.15 for the 600-frame rope), %.2f of the file\n",
              (unsigned long long)f.memory_bytes, double(f.memory_bytes) / double(f.raw_bytes),
              (unsigned long long)f.raw_bytes, double(f.memory_bytes) / double(f.file_bytes));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: runtime_bench FILE.dcrv...\n");
    return 2;
  }
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    Figures f;
    if (measure(argv[i], &f)) print(argv[i], f);
    else status = 1;
  }
  return status;
}
