// PC2 and MDD files: what the writer writes the reader reads back bit for bit with the
// header's rate and start, and a damaged file is refused with its name, never read short.
#include <gtest/gtest.h>

#include <fstream>

#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/point_cache.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

Animation two_frame_triangle() {
  Animation anim;
  anim.vertex_count = 3;
  anim.frames = {{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 0, 1, 1, 0, 1, 0.25f, 1, 1}};
  return anim;
}

bool write_cache(const std::string& path, const Animation& anim, double fps) {
  PointCacheKind kind;
  if (!point_cache_kind(path, &kind)) return false;
  OutputFile out;
  std::string err;
  if (!out.open(path, true, &err)) return false;
  PointCacheWriter w(kind, &out, anim.vertex_count);
  bool ok = w.write_header(uint32_t(anim.frames.size()), fps, 0.0, &err);
  for (const auto& frame : anim.frames) ok = ok && w.write_frame(frame.data(), &err);
  return ok && out.commit(&err);
}

TEST(PointCache, WrittenFramesReadBackExactly) {
  TempDir dir;
  const Animation anim = two_frame_triangle();
  for (const char* name : {"a.pc2", "a.MDD"}) {
    ASSERT_TRUE(write_cache(dir / name, anim, 25.0)) << name;
    Animation back;
    PointCacheInfo info;
    std::string err;
    ASSERT_TRUE(read_point_cache(dir / name, &back, &info, &err)) << err;
    EXPECT_EQ(back.frames, anim.frames) << name;
    EXPECT_EQ(info.vertex_count, 3u);
    EXPECT_EQ(info.frame_count, 2u);
  }
  Animation back;
  PointCacheInfo info;
  std::string err;
  ASSERT_TRUE(read_point_cache(dir / "a.MDD", &back, &info, &err)) << err;
  EXPECT_NEAR(info.frame_rate, 25.0, 1e-3);  // MDD stores a time per frame
  EXPECT_NEAR(back.frame_rate, 25.0, 1e-3);
}

TEST(PointCache, TruncatedOrPaddedFilesAreRefusedByName) {
  TempDir dir;
  for (const char* name : {"t.pc2", "t.mdd"}) {
    ASSERT_TRUE(write_cache(dir / name, two_frame_triangle(), 30.0));
    std::vector<uint8_t> bytes;
    std::string err;
    ASSERT_TRUE(read_file(dir / name, &bytes, &err));
    for (size_t keep : {bytes.size() - 1, bytes.size() - 36, size_t(20), size_t(3), size_t(0)}) {
      std::ofstream(dir / name, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(keep));
      Animation back;
      PointCacheInfo info;
      EXPECT_FALSE(read_point_cache(dir / name, &back, &info, &err)) << name << " cut to " << keep;
      EXPECT_NE(err.find(dir / name), std::string::npos) << err;
    }
    bytes.push_back(0);
    ASSERT_TRUE(write_file_atomic(dir / name, bytes.data(), bytes.size(), &err));
    Animation back;
    PointCacheInfo info;
    EXPECT_FALSE(read_point_cache(dir / name, &back, &info, &err)) << name;
    EXPECT_NE(err.find("trailing bytes"), std::string::npos) << err;
  }
}

TEST(PointCache, NonFiniteValueIsRefused) {
  TempDir dir;
  Animation anim = two_frame_triangle();
  anim.frames[1][4] = std::numeric_limits<float>::quiet_NaN();
  ASSERT_TRUE(write_cache(dir / "n.pc2", anim, 30.0));
  Animation back;
  PointCacheInfo info;
  std::string err;
  EXPECT_FALSE(read_point_cache(dir / "n.pc2", &back, &info, &err));
  EXPECT_NE(err.find("frame 1, vertex 1"), std::string::npos) << err;
}

// 1,380,655,685 x 3,340,214,413 = 2^62 + 1, so frames x vertices x 12 bytes wraps around 64
// bits to exactly one vertex's 12 bytes: a size check done by multiplying would accept the
// file and then size a billion frames.
TEST(PointCache, HeaderWhoseSizeWrapsAroundIsRefused) {
  TempDir dir;
  Animation one_vertex;
  one_vertex.vertex_count = 1;
  one_vertex.frames = {{1, 2, 3}};
  ASSERT_TRUE(write_cache(dir / "w.pc2", one_vertex, 30.0));
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(read_file(dir / "w.pc2", &bytes, &err));
  auto put_u32 = [&](size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes[at + i] = uint8_t(v >> (8 * i));
  };
  put_u32(16, 3340214413u);  // vertices
  put_u32(28, 1380655685u);  // frames
  ASSERT_TRUE(write_file_atomic(dir / "w.pc2", bytes.data(), bytes.size(), &err));
  Animation back;
  PointCacheInfo info;
  EXPECT_FALSE(read_point_cache(dir / "w.pc2", &back, &info, &err));
  EXPECT_NE(err.find("truncated file?"), std::string::npos) << err;
  EXPECT_TRUE(back.frames.empty());
}

}  // namespace
}  // namespace dcurve::test
