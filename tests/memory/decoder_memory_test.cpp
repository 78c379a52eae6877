// The runtime decoder's memory does not grow with the clip: a file of 600 frames plays frame
// by frame within the same bound as one of 300, checked through memory_bytes() and through
// every allocation the decoder makes (this program replaces operator new to count them).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <string>
#include <vector>

#include "codec/compress/zstd_frame_writer.h"
#include "codec/decompress/container_reader.h"
#include "tests/container_bytes.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"

namespace {
std::atomic<size_t> live_bytes{0}, peak_bytes{0};
}  // namespace

namespace {
// Every allocation records its size in a header, so the live total is exact. Every form of
// operator new and delete that does not take an alignment is replaced, so each pair agrees.
void* counted_new(size_t size) noexcept {
  void* p = std::malloc(size + 16);
  if (!p) return nullptr;
  *static_cast<size_t*>(p) = size;
  const size_t now = live_bytes += size;
  size_t peak = peak_bytes.load();
  while (now > peak && !peak_bytes.compare_exchange_weak(peak, now)) {
  }
  return static_cast<char*>(p) + 16;
}
void counted_delete(void* p) noexcept {
  if (!p) return;
  void* base = static_cast<char*>(p) - 16;
  live_bytes -= *static_cast<size_t*>(base);
  std::free(base);
}
void* counted_or_throw(size_t size) {
  void* p = counted_new(size);
  if (!p) throw std::bad_alloc();
  return p;
}
}  // namespace

void* operator new(size_t size) { return counted_or_throw(size); }
void* operator new[](size_t size) { return counted_or_throw(size); }
void* operator new(size_t size, const std::nothrow_t&) noexcept { return counted_new(size); }
void* operator new[](size_t size, const std::nothrow_t&) noexcept { return counted_new(size); }
void operator delete(void* p) noexcept { counted_delete(p); }
void operator delete[](void* p) noexcept { counted_delete(p); }
void operator delete(void* p, size_t) noexcept { counted_delete(p); }
void operator delete[](void* p, size_t) noexcept { counted_delete(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { counted_delete(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { counted_delete(p); }

namespace dcurve {
namespace {

constexpr uint32_t kSide = 12, kChunkFrames = 16;

// A square sheet of kSide x kSide vertices under a travelling wave: every frame differs, so
// every chunk has residuals to decode.
Animation wave(uint32_t frames) {
  Animation a;
  a.vertex_count = kSide * kSide;
  for (uint32_t r = 0; r + 1 < kSide; ++r)
    for (uint32_t c = 0; c + 1 < kSide; ++c) {
      const uint32_t v = r * kSide + c;
      a.faces.insert(a.faces.end(), {v, v + 1, v + kSide, v + kSide, v + 1, v + kSide + 1});
    }
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t v = 0; v < a.vertex_count; ++v) {
      const float x = float(v % kSide), y = float(v / kSide);
      xyz.insert(xyz.end(), {x, y, 0.8f * std::sin(0.5f * x + 0.11f * float(f)) * std::cos(0.3f * y - 0.07f * float(f))});
    }
    a.frames.push_back(xyz);
  }
  return a;
}

struct Playback {
  size_t memory_bytes = 0;  // decoder + cursor after every frame was played, as they report it
  size_t live_bytes = 0;    // the heap they hold then, as counted
  size_t peak_bytes = 0;    // most bytes live at once from opening to the last frame
  size_t raw_bytes = 0;
};

Playback play(uint32_t frames, const std::string& path, Profile profile = Profile::Small) {
  EncodeOptions o;
  o.profile = profile;
  o.grid_refinement = 2;
  o.low_rank = 0;
  o.chunk_frames = kChunkFrames;
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(wave(frames), o, &bytes, nullptr, &err)) << err;
  EXPECT_TRUE(write_file_atomic(path, bytes.data(), bytes.size(), &err)) << err;
  bytes = {};
  Playback p;
  const size_t before = live_bytes;
  peak_bytes = before;
  {
    auto dec = Decoder::open_file(path, &err);
    EXPECT_TRUE(dec) << err;
    if (!dec) return p;
    EXPECT_EQ(dec->chunk_frames(), kChunkFrames);
    auto cursor = dec->make_cursor();
    const size_t held = live_bytes;
    std::vector<float> xyz(size_t(dec->vertex_count()) * 3);
    const size_t output = live_bytes - held;  // the caller's buffer, not the decoder's
    for (uint32_t f = 0; f < dec->frame_count(); ++f) EXPECT_TRUE(cursor->evaluate_frame(f, xyz.data())) << f;
    // In-betweens by a cubic rule too: the cursor then also keeps up to six stencil frames.
    cursor->set_interpolation(Interpolation::Hermite4);
    for (uint32_t f = 0; f + 1 < dec->frame_count(); ++f)
      EXPECT_TRUE(cursor->evaluate((f + 0.5) / (dec->frame_count() - 1), xyz.data())) << f;
    p.memory_bytes = dec->memory_bytes() + cursor->memory_bytes();
    p.live_bytes = live_bytes - before - output;
    p.peak_bytes = peak_bytes - before - output;
    p.raw_bytes = size_t(12) * dec->vertex_count() * dec->frame_count();
  }
  std::remove(path.c_str());
  return p;
}

// Plays 300 and 600 frames of `profile` and checks both against `bound` (bytes) and each other.
void expect_bounded_playback(Profile profile, size_t bound, const char* label) {
  const std::string stem = std::string("/tmp/dcurve_memory_") + label;
  const Playback short_clip = play(300, stem + "_300.dcrv", profile);
  const Playback long_clip = play(600, stem + "_600.dcrv", profile);
  for (const Playback* p : {&short_clip, &long_clip}) {
    EXPECT_LE(p->memory_bytes, bound);
    EXPECT_LE(p->peak_bytes, bound);
    // What memory_bytes() reports is what the decoder holds: within a quarter of the heap it
    // holds (bookkeeping aside).
    EXPECT_GE(p->memory_bytes * 4, p->live_bytes * 3) << p->memory_bytes << " vs live " << p->live_bytes;
    EXPECT_LE(p->memory_bytes * 3, p->live_bytes * 4) << p->memory_bytes << " vs live " << p->live_bytes;
  }
  // Twice the frames: the chunk index grows (a few bytes per chunk), nothing else. The peak
  // also holds buffers sized by the largest chunk and the spatial modes the file uses, which
  // vary with the content by a few KB either way; growing with the clip would add 12 bytes
  // per vertex and frame, 0.5 MB here.
  EXPECT_LE(long_clip.memory_bytes, short_clip.memory_bytes + 2048);
  EXPECT_LE(long_clip.peak_bytes, short_clip.peak_bytes + short_clip.peak_bytes / 8);
  EXPECT_LT(double(long_clip.memory_bytes), 0.15 * double(long_clip.raw_bytes));
  std::printf("%s, memory after playback: 300 frames %zu bytes (live %zu, peak %zu), 600 frames %zu bytes (live %zu, "
              "peak %zu, %.3f of raw)\n",
              label, short_clip.memory_bytes, short_clip.live_bytes, short_clip.peak_bytes, long_clip.memory_bytes,
              long_clip.live_bytes, long_clip.peak_bytes, double(long_clip.memory_bytes) / double(long_clip.raw_bytes));
}

// The bound dcurve.hpp states for a file read from disk: two decoded chunks of int32 values
// and the decoding buffers (residual bytes, one frame of predictions, read buffer), 40 bytes
// per vertex and chunk frame, plus the shared tables and bookkeeping, 256 bytes per vertex
// and 64 KiB.
TEST(DecoderMemory, PlaybackStaysWithinABoundThatDoesNotGrowWithTheFrameCount) {
  const size_t V = kSide * kSide;
  expect_bounded_playback(Profile::Small, 40 * V * kChunkFrames + 256 * V + 65536, "small");
}

// Format 4 (the fast profile): the cursor holds three decoded frames and two frames of Model
// prediction (60 bytes per vertex; a spatial frame recomputes its corrections), never a
// chunk, so the bound has no chunk term.
TEST(DecoderMemory, FastPlaybackHoldsFramesNotChunksAndDoesNotGrow) {
  const size_t V = kSide * kSide;
  expect_bounded_playback(Profile::Fast, 60 * V + 256 * V + 65536, "fast");
}


// A 4 x 4 sheet with render vertices, whose REND section is replaced by one of `groups` face
// groups under zstd: 2 bytes each (no material, an empty name), read into 48 bytes each. The
// first two groups' names, 1424 random bytes, keep the frame within the 4096:1 a reader accepts.
std::vector<uint8_t> file_with_groups(uint64_t groups) {
  Animation a;
  a.vertex_count = 16;
  a.faces = {0, 1, 4, 1, 5, 4};
  for (int f = 0; f < 2; ++f) {
    a.frames.emplace_back();
    for (uint32_t v = 0; v < 16; ++v) a.frames.back().insert(a.frames.back().end(), {float(v % 4), float(v / 4), 0.1f * f * v});
  }
  for (uint32_t v = 0; v < 16; ++v) a.render.source.push_back(v);
  a.render.corners = a.faces;
  a.render.groups = {{-1, "g"}};
  a.render.face_group = {0, 0};
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_TRUE(encode_animation(a, EncodeOptions(), &bytes, nullptr, &err)) << err;
  ByteWriter rend;
  rend.u8(1);
  rend.varint(16);
  for (int i = 0; i < 16 + 6; ++i) rend.varint(0);  // each vertex new, each corner its first copy
  rend.u8(0);                                          // no attributes
  rend.varint(groups);
  std::mt19937 random(11);
  std::string name(1424, ' ');
  for (char& c : name) c = char(random());
  for (uint64_t g = 0; g < groups; ++g) {
    rend.varint(0);
    rend.str(g == 0 ? name.substr(0, 1024) : g == 1 ? name.substr(1024) : "");
  }
  rend.varint(0);
  rend.varint(0);
  testing::RawFile f = testing::split_file(bytes);
  for (testing::RawSection& s : f.sections)
    if (s.tag == "REND") s = {"REND", 2, zstd_frame(rend.data(), 19), rend.size()};
  return testing::assemble(f);
}

// Reading REND stays within the value budget of section 15 (4 bytes per value of
// max(2^23, 8192 * file bytes)): a file of 4.2 million raw REND bytes in 1.7 KB (which would
// take 100 MB) is refused before they are decompressed, one of 0.8 million is read within it.
TEST(DecoderMemory, RenderSectionsAreReadWithinTheValueBudget) {
  for (uint64_t groups : {2100000, 400000}) {
    const std::vector<uint8_t> file = file_with_groups(groups);
    const size_t budget = 4 * decoder_value_budget(file.size());
    const size_t before = live_bytes;
    peak_bytes = before;
    std::string err;
    const bool opened = Decoder::open_memory(file.data(), file.size(), &err) != nullptr;
    const size_t peak = peak_bytes - before;
    EXPECT_LE(peak, budget) << groups << " groups in " << file.size() << " bytes";
    EXPECT_EQ(opened, groups == 400000) << err;
    std::printf("%llu groups in %zu bytes: %s, peak %zu bytes, budget %zu\n", (unsigned long long)groups, file.size(),
                opened ? "read" : err.c_str(), peak, budget);
  }
}

}  // namespace
}  // namespace dcurve
