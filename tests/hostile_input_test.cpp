// Hostile input at the library level (issue 47, input side): the glTF resource policy, limits
// checked before allocating, validation of strides, key and frame times, degenerate triangles
// and coordinate ranges, point caches that are special files, escaped messages, and worker
// threads whose allocation fails. Each input is made here, in a temporary folder.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>

#include "encoder/io/files.h"
#include "encoder/io/gltf_reader.h"
#include "encoder/io/point_cache.h"
#include "encoder/io/quoted_text.h"
#include "encoder/parallel.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace dcurve::test {
namespace {
using nlohmann::json;
namespace fs = std::filesystem;

// Writes `j` as DIR/name and reads it; the message when refused ("" when read).
std::string read_gltf(const std::string& path, const json& j, const ReadLimits& limits = ReadLimits()) {
  std::ofstream(path) << j.dump();
  Animation anim;
  std::string err;
  return read_gltf_animation(path, -1, &anim, &err, limits) ? "" : err;
}

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

// --- 1. Resource policy -------------------------------------------------------------------

TEST(HostileGltfResources, UrisLeavingTheFolderAreRefused) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  write_triangle_buffer(dir / "outside.bin");
  fs::create_symlink(dir / "outside.bin", dir / "asset/link.bin");
  const std::pair<std::string, std::string> cases[] = {
      {"../outside.bin", "outside the glTF's folder"},
      {"sub/../../outside.bin", "outside the glTF's folder"},
      {"link.bin", "outside the glTF's folder"},  // a link inside that points outside
      {dir / "outside.bin", "absolute path"},
      {"file://" + (dir / "outside.bin"), "scheme"},
      {"%2e%2e/outside.bin", "outside the glTF's folder"},
      {"bad%zzescape.bin", "%-escape"},
  };
  for (const auto& [uri, expected] : cases) {
    json j = triangle_gltf();
    j["buffers"][0]["uri"] = uri;
    const std::string err = read_gltf(dir / "asset/t.gltf", j);
    EXPECT_TRUE(contains(err, expected)) << uri << ": " << err;
  }
}

TEST(HostileGltfResources, NoOtherFolderIsSearched) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  write_triangle_buffer(dir / "buf.bin");  // in the current folder, not the glTF's
  const fs::path old = fs::current_path();
  fs::current_path(dir.path);
  const std::string err = read_gltf(dir / "asset/t.gltf", triangle_gltf());
  fs::current_path(old);
  EXPECT_TRUE(contains(err, "no such file in the glTF's folder")) << err;
}

TEST(HostileGltfResources, AnExplicitFolderWidensThePolicy) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  fs::create_directories(dir / "shared");
  write_triangle_buffer(dir / "shared/buf.bin");
  json j = triangle_gltf();
  j["buffers"][0]["uri"] = "../shared/buf.bin";
  EXPECT_NE(read_gltf(dir / "asset/t.gltf", j), "");
  ReadLimits limits;
  limits.resource_dirs = {dir / "shared"};
  EXPECT_EQ(read_gltf(dir / "asset/t.gltf", j, limits), "");
}

TEST(HostileGltfResources, SpecialFilesAreRefusedWithoutWaiting) {
  TempDir dir;
  ASSERT_EQ(mkfifo((dir / "fifo.bin").c_str(), 0600), 0);
  fs::create_directories(dir / "folder.bin");
  const std::pair<std::string, std::string> cases[] = {
      {"fifo.bin", "is a FIFO"}, {".", "is a folder"}, {"folder.bin", "is a folder"}, {"missing.bin", "no such file"}};
  for (const auto& [uri, expected] : cases) {
    json j = triangle_gltf();
    j["buffers"][0]["uri"] = uri;
    const std::string err = read_gltf(dir / "t.gltf", j);
    EXPECT_TRUE(contains(err, expected)) << uri << ": " << err;
  }
}

TEST(HostileGltfResources, ImagesAndUnusedBuffersAreNeverOpened) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  ASSERT_EQ(mkfifo((dir / "image.png").c_str(), 0600), 0);  // opening it for reading would hang
  ASSERT_EQ(mkfifo((dir / "unused.bin").c_str(), 0600), 0);
  json j = triangle_gltf();
  j["images"] = json::array({{{"uri", "image.png"}}, {{"uri", "."}}, {{"uri", "../../../../etc/passwd"}}});
  j["buffers"].push_back({{"uri", "unused.bin"}, {"byteLength", 64}});
  j["buffers"].push_back({{"uri", "../../nowhere.bin"}, {"byteLength", 64}});
  j["bufferViews"].push_back({{"buffer", 1}, {"byteLength", 64}});
  j["images"].push_back({{"bufferView", 5}, {"mimeType", "image/png"}});
  EXPECT_EQ(read_gltf(dir / "t.gltf", j), "");
}

// An image is read only when a material of the mesh uses it, and then under the same policy
// as buffers: a file inside the glTF's folder, regular, no other.
TEST(HostileGltfResources, AMaterialsImagesAreReadUnderThePolicy) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  write_triangle_buffer(dir / "asset/buf.bin");
  write_bytes(dir / "secret.png", "\x89PNG\r\n\x1a\nsecret");
  write_bytes(dir / "asset/tex.png", "\x89PNG\r\n\x1a\npixels");
  ASSERT_EQ(mkfifo((dir / "asset/fifo.png").c_str(), 0600), 0);  // opening it for reading would hang
  json j = triangle_gltf();
  j["materials"] = json::array({{{"name", "cloth"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  j["textures"] = json::array({{{"source", 0}}});
  j["meshes"][0]["primitives"][0]["material"] = 0;
  for (const char* uri : {"../secret.png", "fifo.png"}) {
    j["images"] = json::array({{{"uri", uri}}});
    const std::string err = read_gltf(dir / "asset/t.gltf", j);
    EXPECT_TRUE(contains(err, "image 0")) << uri << ": " << err;
    EXPECT_TRUE(contains(err, std::string(uri) == "fifo.png" ? "FIFO" : "leads outside the glTF's folder")) << err;
  }
  j["images"] = json::array({{{"uri", "tex.png"}}});
  std::ofstream(dir / "asset/t.gltf") << j.dump();
  Animation anim;
  std::string err;
  ASSERT_TRUE(read_gltf_animation(dir / "asset/t.gltf", -1, &anim, &err)) << err;
  ASSERT_EQ(anim.materials.images.size(), 1u);
  EXPECT_EQ(std::string(anim.materials.images[0].bytes.begin(), anim.materials.images[0].bytes.end()),
            "\x89PNG\r\n\x1a\npixels");
  EXPECT_EQ(anim.materials.images[0].mime_type, "image/png");
  ASSERT_EQ(anim.render.groups.size(), 1u);
  EXPECT_EQ(anim.render.groups[0].name, "cloth");
}

// Found by the reader fuzzer: a mesh that is not an object, looked at before tinygltf parses
// the file (which images a material uses), read a destroyed temporary (ASan catches it).
TEST(HostileGltfResources, MeshesThatAreNotObjectsAreRefusedCleanly) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  j["meshes"].push_back(5);
  j["meshes"].push_back({{"primitives", 7}});
  EXPECT_NE(read_gltf(dir / "t.gltf", j), "");
}

TEST(HostileGltfResources, BufferSizeMustMatchItsFileAndDataUrisAreBounded) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  j["buffers"][0]["byteLength"] = 96;  // the file has 100 bytes
  EXPECT_TRUE(contains(read_gltf(dir / "t.gltf", j), "100 bytes, but its byteLength is 96"));
  j = triangle_gltf();
  j["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(40000, 'A');
  const std::string err = read_gltf(dir / "t.gltf", j);
  EXPECT_TRUE(contains(err, "data: uri is")) << err;
  EXPECT_LT(err.size(), 400u) << "the uri is not repeated";
}

// --- 2. Limits before allocating ----------------------------------------------------------

TEST(HostileGltfLimits, DeepJsonIsAnErrorNotAStackOverflow) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  for (const std::string& open_close : {std::string("[]"), std::string("{}")}) {
    std::string deep;
    for (int i = 0; i < 30000; ++i) deep += open_close[0] == '[' ? "[" : "{\"a\":";
    deep += "1";
    for (int i = 0; i < 30000; ++i) deep += open_close[1];
    std::string text = triangle_gltf().dump();
    text.insert(text.size() - 1, ",\"extras\":" + deep);
    write_bytes(dir / "t.gltf", text);
    Animation anim;
    std::string err;
    EXPECT_FALSE(read_gltf_animation(dir / "t.gltf", -1, &anim, &err));
    EXPECT_TRUE(contains(err, "nested deeper than")) << err;
  }
}

TEST(HostileGltfLimits, DeclaredCountsAreCheckedAgainstTheBudget) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  ReadLimits small;
  small.max_memory = 64 << 20;
  // Accessors without a bufferView are zeros: a few bytes may declare millions of vertices.
  json j = triangle_gltf();
  j["accessors"][0].erase("bufferView");
  j["accessors"][0]["count"] = 60000000;
  j["accessors"][1].erase("bufferView");
  j["accessors"][1]["count"] = 60000000;
  j["meshes"][0]["primitives"][0].erase("indices");
  EXPECT_TRUE(contains(read_gltf(dir / "t.gltf", j, small), "--max-memory"));
  // A byteLength beyond the budget is refused before the file is read.
  j = triangle_gltf();
  j["buffers"][0]["byteLength"] = uint64_t(1) << 40;
  EXPECT_TRUE(contains(read_gltf(dir / "t.gltf", j), "--max-memory"));
  // Many keys of few vertices: the frames are counted too.
  j = triangle_gltf();
  j["accessors"][3].erase("bufferView");
  j["accessors"][3]["count"] = 50000000;
  EXPECT_TRUE(contains(read_gltf(dir / "t.gltf", j, small), "--max-memory"));
}

TEST(HostileGltfLimits, EmptyMorphTargetsCostNothing) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  for (int a : {0, 1}) {  // 3,000 vertices of zeros (no bufferView)
    j["accessors"][a].erase("bufferView");
    j["accessors"][a]["count"] = 3000;
  }
  j["meshes"][0]["primitives"][0].erase("indices");
  auto& targets = j["meshes"][0]["primitives"][0]["targets"];
  for (int t = 0; t < 100000; ++t) targets.push_back(json::object());
  j["accessors"][4].erase("bufferView");  // the weights: zeros
  j["accessors"][4]["count"] = 2 * 100001;
  ReadLimits small;
  small.max_memory = 16 << 20;  // an array per empty target would take 100,000 x 36 KB
  EXPECT_EQ(read_gltf(dir / "t.gltf", j, small), "");
}

TEST(HostileGltfLimits, WorkerExceptionsReachTheCaller) {
  for (int threads : {1, 2, 4}) {
    EXPECT_THROW(parallel_for(16, threads,
                              [](size_t i) {
                                if (i == 5) throw std::bad_alloc();
                              }),
                 std::bad_alloc)
        << threads;
  }
}

// --- 3. Validation as the specs say -------------------------------------------------------

TEST(HostileGltfValidation, ByteStrideMustHoldAnElementAndBeAligned) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  for (int stride : {4, 8, 14}) {
    json j = triangle_gltf();
    j["bufferViews"][0]["byteStride"] = stride;
    j["bufferViews"][0]["byteLength"] = 36;
    const std::string err = read_gltf(dir / "t.gltf", j);
    EXPECT_TRUE(contains(err, "byteStride") && contains(err, std::to_string(stride))) << err;
  }
}

// The fixture with key times `times` (2 keys: the buffer holds 2).
std::string read_with_times(const TempDir& dir, float t0, float t1) {
  write_triangle_buffer(dir / "buf.bin");
  std::fstream f(dir / "buf.bin", std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(84);
  f.write(reinterpret_cast<const char*>(&t0), 4).write(reinterpret_cast<const char*>(&t1), 4);
  f.close();
  return read_gltf(dir / "t.gltf", triangle_gltf());
}

TEST(HostileGltfValidation, KeyTimesMustBeFiniteIncreasingAndAtACliRate) {
  TempDir dir;
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(contains(read_with_times(dir, 0, nan), "not a finite number"));
  EXPECT_TRUE(contains(read_with_times(dir, nan, 1), "not a finite number"));
  EXPECT_TRUE(contains(read_with_times(dir, 0, inf), "not a finite number"));
  EXPECT_TRUE(contains(read_with_times(dir, 1, 0), "do not increase"));
  EXPECT_TRUE(contains(read_with_times(dir, 0, 1e-40f), "frames per second, outside"));
  EXPECT_TRUE(contains(read_with_times(dir, 0, 1e5f), "frames per second, outside"));
  EXPECT_EQ(read_with_times(dir, 0, 0.04f), "");
}

TEST(HostileGltfValidation, DegenerateTrianglesAreRefusedLikeTheObjReader) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  j["meshes"][0]["primitives"][0].erase("indices");  // 0 1 2: fine
  EXPECT_EQ(read_gltf(dir / "t.gltf", j), "");
  std::fstream f(dir / "buf.bin", std::ios::in | std::ios::out | std::ios::binary);
  const uint32_t idx[3] = {0, 1, 1};
  f.seekp(72);
  f.write(reinterpret_cast<const char*>(idx), 12);
  f.close();
  EXPECT_TRUE(contains(read_gltf(dir / "t.gltf", triangle_gltf()), "uses a vertex twice"));
  // The same rule in the OBJ reader and in the mesh writer.
  write_bytes(dir / "d.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 2\n");
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  EXPECT_FALSE(read_mesh(dir / "d.obj", &xyz, &faces, &err));
  const float three[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_FALSE(write_mesh(dir / "w.obj", three, 3, {0, 1, 1}, &err));
  EXPECT_TRUE(contains(err, "uses a vertex twice")) << err;
  EXPECT_FALSE(fs::exists(dir / "w.obj"));
}

TEST(HostileGltfValidation, OutOfRangeCoordinatesAreInputErrors) {
  TempDir dir;
  for (float big : {1e37f, -1e30f, 1e19f}) {
    write_triangle_buffer(dir / "buf.bin");
    std::fstream f(dir / "buf.bin", std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(4);
    f.write(reinterpret_cast<const char*>(&big), 4);
    f.close();
    const std::string err = read_gltf(dir / "t.gltf", triangle_gltf());
    EXPECT_TRUE(contains(err, "a coordinate is not finite and within")) << big << ": " << err;
  }
  write_bytes(dir / "big.obj", "v 0 0 0\nv 1e37 0 0\nv 0 1 0\nf 1 2 3\n");
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  EXPECT_FALSE(read_mesh(dir / "big.obj", &xyz, &faces, &err));
  EXPECT_TRUE(contains(err, "a coordinate is not finite and within")) << err;
}

// --- 3b. MDD frame times ------------------------------------------------------------------

// An MDD of one vertex with the given frame times.
std::string mdd_with_times(const std::vector<float>& times) {
  std::string b;
  auto u32 = [&b](uint32_t u) {
    for (int i = 0; i < 4; ++i) b.push_back(char(u >> (24 - 8 * i)));
  };
  auto f32 = [&u32](float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    u32(u);
  };
  u32(uint32_t(times.size()));
  u32(1);
  for (float t : times) f32(t);
  for (size_t f = 0; f < times.size(); ++f)
    for (int a = 0; a < 3; ++a) f32(float(f + a));
  return b;
}

TEST(HostilePointCache, MddFrameTimesAreHonouredOrRefused) {
  TempDir dir;
  const std::pair<std::vector<float>, std::string> cases[] = {
      {{0, .01f, .02f, .03f, 10}, "not evenly spaced"},
      {{0, .02f, .01f}, "do not increase"},
      {{0, std::numeric_limits<float>::quiet_NaN(), .02f}, "not a finite number"},
      {{std::numeric_limits<float>::quiet_NaN()}, "not a finite number"},
      {{0, 1e-30f}, "frames per second, outside"},
  };
  for (const auto& [times, expected] : cases) {
    write_bytes(dir / "c.mdd", mdd_with_times(times));
    Animation anim;
    PointCacheInfo info;
    std::string err;
    EXPECT_FALSE(read_point_cache(dir / "c.mdd", &anim, &info, &err));
    EXPECT_TRUE(contains(err, expected)) << err;
    EXPECT_TRUE(contains(err, dir / "c.mdd")) << err;
  }
  write_bytes(dir / "c.mdd", mdd_with_times({1, 1.04f, 1.08f, 1.12f}));
  Animation anim;
  PointCacheInfo info;
  std::string err;
  ASSERT_TRUE(read_point_cache(dir / "c.mdd", &anim, &info, &err)) << err;
  EXPECT_NEAR(info.frame_rate, 25.0, 1e-3);
}

// --- 4. Point caches and meshes that are special files ------------------------------------

TEST(HostilePointCache, SpecialFilesAreRefusedByWhatTheyAre) {
  TempDir dir;
  fs::create_symlink("/dev/zero", dir / "zero.pc2");
  fs::create_symlink("/dev/zero", dir / "zero.mdd");
  ASSERT_EQ(mkfifo((dir / "fifo.pc2").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
  fs::create_directories(dir / "folder.mdd");
  for (const auto& [name, expected] : std::vector<std::pair<std::string, std::string>>{
           {"zero.pc2", "is a device"}, {"zero.mdd", "is a device"}, {"fifo.pc2", "is a FIFO"}, {"folder.mdd", "is a folder"}}) {
    Animation anim;
    PointCacheInfo info;
    std::string err;
    EXPECT_FALSE(read_point_cache(dir / name, &anim, &info, &err));
    EXPECT_TRUE(contains(err, dir / name) && contains(err, expected)) << err;
  }
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  EXPECT_FALSE(read_mesh(dir / "fifo.obj", &xyz, &faces, &err));
  EXPECT_TRUE(contains(err, "is a FIFO")) << err;
}

TEST(HostilePointCache, FileSizeIsCheckedBeforeReading) {
  TempDir dir;
  std::string pc2(32, '\0');
  std::memcpy(&pc2[0], "POINTCACHE2", 12);
  pc2[16] = 1;  // 1 vertex
  pc2[28] = 2;  // 2 frames
  pc2 += std::string(24, '\0');
  write_bytes(dir / "ok.pc2", pc2);
  Animation anim;
  PointCacheInfo info;
  std::string err;
  ASSERT_TRUE(read_point_cache(dir / "ok.pc2", &anim, &info, &err)) << err;
  EXPECT_FALSE(read_point_cache(dir / "ok.pc2", &anim, &info, &err, 100));
  EXPECT_TRUE(contains(err, "more than the limit")) << err;
}

// --- 5. Messages --------------------------------------------------------------------------

TEST(HostileMessages, FileTextIsEscapedAndCut) {
  EXPECT_EQ(quote_file_text("a\x1b[31mb\n"), "a\\x1b[31mb\\x0a");
  EXPECT_EQ(quote_file_text("back\\slash"), "back\\\\slash");
  EXPECT_EQ(quote_file_text("\xc2\x9b" "2J"), "\\xc2\\x9b2J");       // C1 CSI in UTF-8
  EXPECT_EQ(quote_file_text("caf\xc3\xa9 \xe6\x97\xa5"), "caf\xc3\xa9 \xe6\x97\xa5");  // UTF-8 kept
  EXPECT_EQ(quote_file_text("\xff\xfe"), "\\xff\\xfe");
  const std::string cut = quote_file_text(std::string(100000, 'x'));
  EXPECT_LT(cut.size(), 260u);
  EXPECT_TRUE(contains(cut, "(100000 bytes)"));
}

TEST(HostileMessages, GltfMessagesQuoteUrisAndNamesSafely) {
  TempDir dir;
  json j = triangle_gltf();
  j["buffers"][0]["uri"] = "\x1b]0;pwned\x07../" + std::string(5000, 'a');
  std::string err = read_gltf(dir / "t.gltf", j);
  EXPECT_EQ(err.find('\x1b'), std::string::npos) << err;
  EXPECT_TRUE(contains(err, "\\x1b]0;pwned\\x07")) << err;
  EXPECT_LT(err.size(), 700u);
  write_triangle_buffer(dir / "buf.bin");
  j = triangle_gltf();
  j["meshes"].push_back(j["meshes"][0]);
  j["meshes"][1]["name"] = "\x1b[2J" + std::string(3000, 'n');
  err = read_gltf(dir / "t.gltf", j);
  EXPECT_TRUE(contains(err, "holds 2 meshes")) << err;
  EXPECT_EQ(err.find('\x1b'), std::string::npos);
  EXPECT_LT(err.size(), 700u);
}

}  // namespace
}  // namespace dcurve::test
