// The streaming decoder (format 3.0): chunks decode on demand and alone, a damaged chunk
// fails the call that needs it and nothing else, a file changed after open_file is
// detected, cursors play in order and in parallel, and the C ABI reports named codes.
#include <gtest/gtest.h>
#include <zstd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include "container_bytes.h"
#include "decoder/dcurve.h"
#include "decoder/dcurve.hpp"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "test_models.h"
#include "test_util.h"

namespace dcurve {
namespace {

constexpr uint32_t kFrames = 10, kChunk = 4;  // chunks of frames 0-3, 4-7, 8-9

// small_model's grid values coded in chunks of `chunk` frames.
std::vector<uint8_t> chunked_file(uint32_t chunk) {
  Model m = testing::small_model(kFrames);
  m.residual.payload = encode_residuals(m, testing::grid(m.meta.vertex_count, kFrames),
                                        default_chunked_plan(kFrames, chunk));
  return write_container(m);
}

// Every frame and the in-betweens around each chunk boundary, as floats.
std::vector<std::vector<float>> play(Decoder& d) {
  std::vector<std::vector<float>> out;
  auto cursor = d.make_cursor();
  for (int k = 0; k <= 4 * int(kFrames - 1); ++k) {
    std::vector<float> xyz(size_t(d.vertex_count()) * 3);
    EXPECT_TRUE(cursor->evaluate(k / (4.0 * (kFrames - 1)), xyz.data())) << k;
    out.push_back(xyz);
  }
  return out;
}

TEST(DecoderStream, ChunkedFileDecodesAsTheWholeClipInOneChunk) {
  const std::vector<uint8_t> chunked = chunked_file(kChunk), whole = chunked_file(kFrames);
  std::string err;
  auto a = Decoder::open_memory(chunked.data(), chunked.size(), &err);
  auto b = Decoder::open_memory(whole.data(), whole.size(), &err);
  ASSERT_TRUE(a && b) << err;
  EXPECT_EQ(a->chunk_frames(), kChunk);
  EXPECT_EQ(a->chunk_count(), 3u);
  EXPECT_EQ(b->chunk_count(), 1u);
  EXPECT_EQ(play(*a), play(*b));  // in-betweens across chunk boundaries included
  // Backwards and jumping: the window decodes what each call needs.
  auto cursor = a->make_cursor();
  std::vector<float> x(18), y(18);
  for (uint32_t f : {9u, 0u, 5u, 4u, 3u, 8u, 1u}) {
    ASSERT_TRUE(cursor->evaluate_frame(f, x.data()));
    ASSERT_TRUE(b->evaluate_frame(f, y.data()));
    EXPECT_EQ(x, y) << f;
  }
}

TEST(DecoderStream, CursorsInThreadsGetTheSameFrames) {
  const std::vector<uint8_t> bytes = chunked_file(kChunk);
  std::string err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(d) << err;
  const std::vector<std::vector<float>> serial = play(*d);
  std::vector<std::vector<float>> in_threads[2];
  std::thread t0([&] { in_threads[0] = play(*d); }), t1([&] { in_threads[1] = play(*d); });
  t0.join();
  t1.join();
  EXPECT_EQ(in_threads[0], serial);
  EXPECT_EQ(in_threads[1], serial);
}

struct IndexEntry {
  uint64_t offset = 0, size = 0;
  uint32_t crc = 0;
};

// The RESI section of `bytes` with its chunk index replaced (valid section CRC).
std::vector<uint8_t> with_index(const std::vector<uint8_t>& bytes, uint32_t chunk_frames, uint32_t count,
                                const std::vector<IndexEntry>& chunks) {
  testing::RawFile f = testing::split_file(bytes);
  for (testing::RawSection& s : f.sections) {
    if (s.tag != "RESI") continue;
    std::vector<uint8_t> raw = s.stored;
    if (s.flags & 2) {  // zstd
      raw.resize(size_t(s.raw_size));
      EXPECT_EQ(ZSTD_decompress(raw.data(), raw.size(), s.stored.data(), s.stored.size()), raw.size());
    }
    ByteWriter w;
    w.bytes(raw.data(), 32);  // step and origin
    w.u8(raw[32]);  // the payload version as written
    w.u8(1);
    w.varint(chunk_frames);
    w.varint(count);
    for (const IndexEntry& c : chunks) {
      w.varint(c.offset);
      w.varint(c.size);
      w.u32(c.crc);
    }
    s = testing::plain_section("RESI", true, w.data());
  }
  return testing::assemble(f);
}

TEST(DecoderStream, ChunkIndexThatDisagreesIsRefusedAtOpen) {
  const std::vector<uint8_t> bytes = chunked_file(kChunk);
  // The index as written: offsets from the start of the chunk data, sizes, CRCs.
  Model m;
  std::string err;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  const std::vector<testing::PayloadChunk> chunks = testing::payload_chunks(m.residual.payload);
  ASSERT_EQ(chunks.size(), 3u);
  std::vector<IndexEntry> index;
  for (const testing::PayloadChunk& c : chunks) {
    const uint8_t* crc = m.residual.payload.data() + c.crc_at;
    index.push_back({c.start - chunks[0].start, c.size,
                     uint32_t(crc[0]) | uint32_t(crc[1]) << 8 | uint32_t(crc[2]) << 16 | uint32_t(crc[3]) << 24});
  }
  const std::vector<uint8_t> same = with_index(bytes, kChunk, 3, index);
  EXPECT_TRUE(test::opens_and_decodes(same, &err)) << "the test's index is the writer's: " << err;

  auto refused = [&](const std::vector<uint8_t>& file, const char* why) {
    std::string e;
    EXPECT_FALSE(Decoder::open_memory(file.data(), file.size(), &e)) << why;
    EXPECT_NE(e.find("chunk"), std::string::npos) << why << ": " << e;
  };
  refused(with_index(bytes, kChunk, 2, {index[0], index[1]}), "count disagrees with the frame count");
  refused(with_index(bytes, 5, 3, index), "chunk length disagrees with the count");
  std::vector<IndexEntry> overlap = index;
  overlap[1].offset -= 1;
  refused(with_index(bytes, kChunk, 3, overlap), "overlapping chunks");
  std::vector<IndexEntry> gap = index;
  gap[2].offset += 1;
  refused(with_index(bytes, kChunk, 3, gap), "a gap between chunks");
  std::vector<IndexEntry> outside = index;
  outside[2].size += 100;
  refused(with_index(bytes, kChunk, 3, outside), "a chunk past the end of the file");
  std::vector<IndexEntry> short_data = index;
  short_data[2].size -= 1;
  refused(with_index(bytes, kChunk, 3, short_data), "chunk data left over");
}

TEST(DecoderStream, DamagedChunkFailsOnlyTheCallsThatNeedIt) {
  std::vector<uint8_t> bytes = chunked_file(kChunk);
  bytes[bytes.size() - 3] ^= 0x40;  // inside the last chunk (frames 8, 9)
  std::string err;
  auto d = Decoder::open_memory(bytes.data(), bytes.size(), &err);
  ASSERT_TRUE(d) << "chunks are checked when a frame needs them: " << err;
  std::vector<float> xyz(18);
  Error e;
  EXPECT_FALSE(d->evaluate_frame(9, xyz.data(), &e));
  EXPECT_EQ(e.status, Status::CorruptChunk);
  EXPECT_NE(e.message.find("chunk 2"), std::string::npos) << e.message;
  for (uint32_t f = 0; f < 8; ++f) EXPECT_TRUE(d->evaluate_frame(f, xyz.data())) << "frame " << f;
  EXPECT_FALSE(d->evaluate(1.0, xyz.data()));
  dcurve_decoder* c = nullptr;
  char msg[128];
  ASSERT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), &c, msg, sizeof msg), DCURVE_OK);
  EXPECT_EQ(dcurve_evaluate_ex(c, 1.0, xyz.data(), msg, sizeof msg), DCURVE_ERROR_CORRUPT_CHUNK);
  EXPECT_NE(std::strstr(msg, "checksum"), nullptr) << msg;
  EXPECT_EQ(dcurve_evaluate_frame(c, 0, xyz.data()), DCURVE_OK);
  dcurve_close(c);
}

TEST(DecoderStream, FileChangedAfterOpenIsDetected) {
  const std::vector<uint8_t> bytes = chunked_file(kChunk);
  test::TempDir dir;
  const std::string path = dir / "clip.dcrv";
  std::string err;
  ASSERT_TRUE(write_file_atomic(path, bytes.data(), bytes.size(), &err)) << err;
  std::vector<float> xyz(18);
  {
    auto d = Decoder::open_file(path, &err);
    ASSERT_TRUE(d) << err;
    std::filesystem::resize_file(path, bytes.size() - 5);  // truncated while open
    Error e;
    EXPECT_TRUE(d->evaluate_frame(0, xyz.data(), &e)) << e.message;
    EXPECT_FALSE(d->evaluate_frame(9, xyz.data(), &e));
    EXPECT_EQ(e.status, Status::Io);
    EXPECT_NE(e.message.find(path), std::string::npos) << e.message;
  }
  ASSERT_TRUE(write_file_atomic(path, bytes.data(), bytes.size(), &err)) << err;
  auto d = Decoder::open_file(path, &err);
  ASSERT_TRUE(d) << err;
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);  // rewritten in place
    f.seekp(std::streamoff(bytes.size() - 3));
    f.put(char(bytes[bytes.size() - 3] ^ 0x40));
  }
  Error e;
  EXPECT_FALSE(d->evaluate_frame(9, xyz.data(), &e));
  EXPECT_EQ(e.status, Status::CorruptChunk);
  EXPECT_TRUE(d->evaluate_frame(1, xyz.data()));
}

TEST(DecoderStream, CAbiVersionCodesAndNullTolerance) {
  EXPECT_EQ(dcurve_version(), uint32_t(DCURVE_VERSION));
  EXPECT_EQ(version(), uint32_t(DCURVE_VERSION));
  EXPECT_STREQ(dcurve_status_name(DCURVE_OK), "ok");
  EXPECT_STREQ(dcurve_status_name(DCURVE_ERROR_CORRUPT_CHUNK), "corrupt chunk");
  EXPECT_STREQ(dcurve_status_name(99), "unknown");
  const std::vector<uint8_t> bytes = chunked_file(kChunk);
  dcurve_decoder* d = nullptr;
  char err[128];
  ASSERT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), &d, err, sizeof err), DCURVE_OK) << err;
  EXPECT_EQ(dcurve_frame_rate(d), 24.0);
  EXPECT_EQ(dcurve_tolerance(d), 1e-3);
  EXPECT_EQ(dcurve_rest_diagonal(d), 3.5);
  EXPECT_EQ(dcurve_chunk_frames(d), kChunk);
  EXPECT_GT(dcurve_memory_bytes(d), 0u);
  dcurve_cursor* c = nullptr;
  ASSERT_EQ(dcurve_cursor_create(d, &c), DCURVE_OK);
  std::vector<float> xyz(18), direct(18);
  EXPECT_EQ(dcurve_cursor_evaluate_frame(c, 6, xyz.data(), err, sizeof err), DCURVE_OK);
  EXPECT_EQ(dcurve_evaluate_frame(d, 6, direct.data()), DCURVE_OK);
  EXPECT_EQ(xyz, direct);
  EXPECT_GT(dcurve_cursor_memory_bytes(c), 0u);
  dcurve_cursor_destroy(c);
  dcurve_close(d);

  EXPECT_EQ(dcurve_open_memory(bytes.data(), 10, &d, err, sizeof err), DCURVE_ERROR_MALFORMED);
  EXPECT_EQ(d, nullptr);
  EXPECT_EQ(dcurve_open_file("/nonexistent/x.dcrv", &d, err, sizeof err), DCURVE_ERROR_IO);
  EXPECT_EQ(dcurve_frame_rate(nullptr), 0.0);
  EXPECT_EQ(dcurve_chunk_frames(nullptr), 0u);
  EXPECT_EQ(dcurve_memory_bytes(nullptr), 0u);
  EXPECT_EQ(dcurve_cursor_create(nullptr, &c), DCURVE_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(c, nullptr);
  EXPECT_EQ(dcurve_cursor_create(d, nullptr), DCURVE_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(dcurve_cursor_evaluate(nullptr, 0.5, xyz.data(), err, sizeof err), DCURVE_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(dcurve_evaluate(nullptr, 0.5, xyz.data()), DCURVE_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(dcurve_cursor_memory_bytes(nullptr), 0u);
  dcurve_cursor_destroy(nullptr);
  dcurve_close(nullptr);
}

}  // namespace
}  // namespace dcurve
