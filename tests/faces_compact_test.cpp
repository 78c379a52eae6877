// FACE layout 2 (Compact): exact round trips of real and awkward triangle lists, a size
// figure that could regress, and rejection of truncated or damaged payloads.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <set>

#include "codec/common/faces.h"
#include "codec/common/faces_compact_walk.h"
#include "codec/common/id_ranks.h"
#include "codec/compress/faces_encoder.h"
#include "codec/decompress/faces_decoder.h"
#include "encoder/io/frames.h"
#include "test_util.h"

namespace dcurve {
namespace {

// The vertex count the hostile streams below are decoded for: room for the grid's ids and
// for a corrupted stream to name ids far from them.
constexpr uint32_t kGridVertices = 1u << 16;

std::vector<uint32_t> compact_roundtrip(const std::vector<uint32_t>& faces, size_t* bytes = nullptr) {
  std::vector<uint8_t> coded = encode_faces(faces, FaceOrder::Compact);
  EXPECT_FALSE(coded.empty());
  EXPECT_EQ(coded.empty() ? -1 : int(coded[0]), int(FaceOrder::Compact));
  if (bytes) *bytes = coded.size();
  std::vector<uint32_t> back;
  std::string err;
  const uint32_t V = faces.empty() ? 0 : *std::max_element(faces.begin(), faces.end()) + 1;
  EXPECT_TRUE(decode_faces(coded.data(), coded.size(), V, &back, &err)) << err;
  return back;
}

std::vector<uint32_t> read_faces(const std::filesystem::path& obj) {
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  EXPECT_TRUE(read_mesh(obj.string(), &xyz, &faces, &err)) << err;
  return faces;
}

// A W x H grid of quads split into two triangles each, vertex ids offset by `base`.
std::vector<uint32_t> grid(uint32_t W, uint32_t H, uint32_t base) {
  std::vector<uint32_t> f;
  for (uint32_t y = 0; y < H; ++y)
    for (uint32_t x = 0; x < W; ++x) {
      const uint32_t v = base + y * (W + 1) + x, up = v + W + 1;
      f.insert(f.end(), {v, v + 1, up + 1, v, up + 1, up});
    }
  return f;
}

// Ranks among unused ids against a plain std::set count, at both ends of the bound and of
// the id range (ids above the bound are all unused).
TEST(IdRanks, RankAndUnrankMatchACountingOracle) {
  const int64_t top = int64_t(UINT32_MAX) - 1;
  const uint32_t bound = (1u << 20) + 4100;  // blocks of 4096 ids: a partial last one
  std::mt19937 rng(5);
  IdRanks ids(bound);
  std::set<int64_t> used;
  for (int i = 0; i < 600; ++i) used.insert(rng() % 2000);
  for (int i = 0; i < 300; ++i) used.insert((int64_t(1) << 20) - 5000 + rng() % 9100);
  for (int64_t v : {int64_t(0), int64_t(1) << 20, (int64_t(1) << 20) + 1, int64_t(bound) - 1}) used.insert(v);
  for (int64_t v : used) ids.insert(uint32_t(v));
  auto used_in = [&](int64_t lo, int64_t hi) {
    return int64_t(std::distance(used.lower_bound(lo), used.upper_bound(hi)));
  };
  auto oracle = [&](int64_t from, int64_t x) -> int64_t {
    if (x == from) return 0;
    const int64_t lo = x > from ? std::max<int64_t>(from + 1, 0) : x, hi = x > from ? x : std::min(from - 1, top);
    const int64_t n = hi - lo + 1 - used_in(lo, hi);
    return x > from ? n : -n;
  };
  EXPECT_EQ(ids.count_below(uint64_t(1) << 32), used.size());
  for (int64_t y = (int64_t(1) << 20) - 5100; y <= int64_t(bound) + 10; ++y)  // across words, blocks, the bound
    ASSERT_EQ(int64_t(ids.count_below(uint64_t(y))), used_in(0, y - 1)) << y;
  const int64_t near_end = int64_t(1) << 20, last = int64_t(bound) - 1;
  for (int64_t from : {int64_t(-7), int64_t(0), int64_t(5), int64_t(999), near_end, last, last + 1, top - 1, top + 1}) {
    for (int64_t x = 0; x < 2100; x += 7)
      for (int64_t probe : {x, top - 1, top - 3, near_end + 2, near_end - 4097 + x, last - 1, last + 1, last + 2}) {
        if (used.count(probe)) continue;
        const int64_t r = ids.rank(from, uint32_t(probe));
        ASSERT_EQ(r, oracle(from, probe)) << from << " " << probe;
        uint32_t back = 0;
        ASSERT_TRUE(ids.unrank(from, r, &back)) << from << " " << r;
        EXPECT_EQ(back, uint32_t(probe)) << from << " " << r;
      }
    uint32_t out = 0;
    EXPECT_FALSE(ids.unrank(from, int64_t(1) << 33, &out));   // more unused ids than exist above
    EXPECT_FALSE(ids.unrank(from, -(int64_t(1) << 33), &out));
  }
  uint32_t out = 0;
  EXPECT_FALSE(ids.unrank(top + 1, 0, &out));  // rank 0 names the prediction itself: out of range
  EXPECT_FALSE(ids.unrank(-1, 0, &out));
}

// A vertex reached again (a known id coded outside the candidate list) keeps the border
// edges it had: encoder and decoder would both forget them alike, so a round trip cannot
// tell, but every file written before would then decode to other triangles.
TEST(FacesCompact, RegionKeepsAVertexsEdgesWhenItIsSeenAgain) {
  faces_compact_walk::Region region(10);
  const uint32_t tri[3] = {0, 1, 2};
  for (uint32_t v : tri) region.mark_seen(v);
  region.add_triangle(tri);
  uint32_t cand[faces_compact_walk::kMaxCandidates];
  int from_a = 0;
  ASSERT_EQ(region.candidates(0, 1, cand, &from_a), 1);  // the open edge 2 -> 0 offers vertex 2
  EXPECT_EQ(cand[0], 2u);
  region.mark_seen(2);
  region.mark_seen(0);
  ASSERT_EQ(region.candidates(0, 1, cand, &from_a), 1);
  EXPECT_EQ(cand[0], 2u);
  EXPECT_EQ(region.fan(2), 1);
  EXPECT_EQ(region.ids().count_below(10), 3u);
}

TEST(FacesCompact, RoundTripsCorpusMeshesInBothOrders) {
  if (!test::have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  const std::filesystem::path corpus = DCURVE_CORPUS_EXT;
  std::vector<std::filesystem::path> meshes;
  for (const char* seq : {"horse-gallop", "chicken-crossing", "elastic-cow", "cloth-sphere", "crane"})
    meshes.push_back(corpus / seq / "frame_00000.obj");
  for (const char* name : {"bunny.obj", "spot.obj"}) meshes.push_back(corpus / "static" / name);
  for (const auto& obj : meshes) {
    if (!std::filesystem::exists(obj)) continue;
    const std::vector<uint32_t> faces = read_faces(obj);
    EXPECT_EQ(compact_roundtrip(faces), faces) << obj;
    const std::vector<uint32_t> trav = traversal_order(faces);
    size_t compact_bytes = 0;
    EXPECT_EQ(compact_roundtrip(trav, &compact_bytes), trav) << obj;
    // Fixed point: reordering the reordered list changes nothing.
    EXPECT_EQ(traversal_order(trav), trav) << obj;
    // In traversal order every corpus mesh costs under 6 bits per triangle (layout 1 needs
    // about 10 after zstd): a regression in the candidate or id coding shows here.
    EXPECT_LT(compact_bytes * 8, 6 * faces.size() / 3) << obj;
  }
}

TEST(FacesCompact, RoundTripsAwkwardLists) {
  const uint32_t big = 65000;  // ids far apart, yet dense enough for the layout (kCompactFreeIds)
  std::vector<std::vector<uint32_t>> lists = {
      {},
      {4, 9, 2},                                   // one triangle
      {0, 1, 2, 2, 1, 3, 0, 1, 4, 1, 0, 5},        // edge 0-1 in three triangles
      {0, 1, 2, 0, 1, 2, 1, 2, 0, 2, 1, 0},        // repeated triangle, same and flipped winding
      {5, 5, 5, 5, 5, 6, 6, 5, 5, 7, 6, 5},        // degenerate triangles
      {big, 0, big - 1, 0, big, 50000, 3, 2, 1, big - 1, 0, 3},  // ids with large gaps
  };
  // Several components and boundaries: two grids with far-apart ids, interleaved.
  std::vector<uint32_t> a = grid(6, 4, 0), b = grid(3, 7, 40000), both;
  for (size_t t = 0; t < std::max(a.size(), b.size()); t += 3) {
    if (t < a.size()) both.insert(both.end(), a.begin() + ptrdiff_t(t), a.begin() + ptrdiff_t(t + 3));
    if (t < b.size()) both.insert(both.end(), b.begin() + ptrdiff_t(t), b.begin() + ptrdiff_t(t + 3));
  }
  lists.push_back(both);
  lists.push_back(traversal_order(both));
  std::mt19937 rng(11);
  for (int n : {2, 50, 3000}) {
    std::vector<uint32_t> soup(size_t(n) * 3);
    for (auto& v : soup) v = rng() % (n < 100 ? 12 : 2000);
    lists.push_back(soup);
    lists.push_back(traversal_order(soup));
  }
  for (const auto& faces : lists) {
    EXPECT_EQ(compact_roundtrip(faces), faces) << faces.size();
    EXPECT_EQ(traversal_order(traversal_order(faces)), traversal_order(faces)) << faces.size();
  }
}

// Ids far sparser than a mesh's (up to 2^32 - 2) would cost the per-vertex state of every
// id below them: the writer declines Compact for Exact, and the list still round trips.
TEST(FacesCompact, SparseIdsFallBackToExact) {
  const std::vector<uint32_t> faces = {UINT32_MAX - 1, 0, 4000000000u, 0, UINT32_MAX - 1, 7};
  const std::vector<uint8_t> coded = encode_faces(faces, FaceOrder::Compact);
  ASSERT_FALSE(coded.empty());
  EXPECT_EQ(int(coded[0]), int(FaceOrder::Exact));
  std::vector<uint32_t> back;
  std::string err;
  EXPECT_TRUE(decode_faces(coded.data(), coded.size(), UINT32_MAX, &back, &err)) << err;
  EXPECT_EQ(back, faces);
  // The same list in the Compact layout (as a hostile file could claim) is refused for a
  // vertex count its ids exceed, before any triangle is built.
  const std::vector<uint32_t> dense = {2, 0, 1, 0, 2, 3};
  std::vector<uint8_t> compact = encode_faces(dense, FaceOrder::Compact);
  ASSERT_EQ(int(compact[0]), int(FaceOrder::Compact));
  EXPECT_TRUE(decode_faces(compact.data(), compact.size(), 4, &back, &err)) << err;
  EXPECT_FALSE(decode_faces(compact.data(), compact.size(), 3, &back, &err));
  EXPECT_NE(err.find("out of range"), std::string::npos) << err;
}

TEST(FacesCompact, RejectsTruncationsFlipsAndAbsurdCounts) {
  const std::vector<uint32_t> faces = traversal_order(grid(5, 4, 100));
  const std::vector<uint8_t> bytes = encode_faces(faces, FaceOrder::Compact);
  std::vector<uint32_t> out;
  std::string err;
  for (size_t n = 0; n < bytes.size(); ++n) EXPECT_FALSE(decode_faces(bytes.data(), n, kGridVertices, &out, &err)) << n;
  // Single-byte changes of the stream: each is either rejected or decodes to some list;
  // none may crash or read outside (run under ASan). Most must be caught.
  size_t rejected = 0, tried = 0;
  for (size_t i = 1; i < bytes.size(); ++i)
    for (int bit = 0; bit < 8; ++bit) {
      std::vector<uint8_t> bad = bytes;
      bad[i] ^= uint8_t(1 << bit);
      ++tried;
      const bool ok = decode_faces(bad.data(), bad.size(), kGridVertices, &out, &err);
      rejected += !ok;
      EXPECT_TRUE(!ok || out.size() % 3 == 0);
    }
  EXPECT_GT(rejected * 2, tried);
  std::vector<uint8_t> bad = {2, 0xFF, 0xFF, 0x03, 0, 0, 0, 0, 0};  // 65535 triangles from 5 bytes
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), kGridVertices, &out, &err));
  EXPECT_NE(err.find("count"), std::string::npos) << err;
  bad = {2, 0x80};  // truncated count
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), kGridVertices, &out, &err));
  bad = {2, 0x10, 0, 0, 0, 0, 0};  // 16 triangles from an all-zero stream
  EXPECT_FALSE(decode_faces(bad.data(), bad.size(), kGridVertices, &out, &err));
  // Random streams: any outcome but a crash, and never more triangles than claimed.
  std::mt19937 rng(3);
  for (int i = 0; i < 3000; ++i) {
    std::vector<uint8_t> noise(size_t(6 + rng() % 60));
    for (auto& b : noise) b = uint8_t(rng());
    noise[0] = 2;
    noise[1] = uint8_t(rng() % 100);
    const bool ok = decode_faces(noise.data(), noise.size(), kGridVertices, &out, &err);
    EXPECT_TRUE(!ok || out.size() == size_t(noise[1]) * 3);
  }
}

}  // namespace
}  // namespace dcurve
