// Hostile assets, round two (issue 59, input side): OBJ files whose mtllib points anywhere,
// many or odd material names, comments after records; PC2 start frames no output can hold;
// '+' in glTF uris. Each input is made here, in a temporary folder.
#include <gtest/gtest.h>
#include <sys/inotify.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>
#include <limits>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "corpus/input.h"
#include "encoder/io/frames.h"
#include "encoder/io/gltf_reader.h"
#include "encoder/io/obj_corners.h"
#include "encoder/io/obj_reader.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace dcurve::test {
namespace hostile_obj {  // named: the sanitized build batches test files together
namespace fs = std::filesystem;

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

const char kTriangle[] = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

// Reads `path` with its corners; the message when refused ("" when read).
std::string read_obj_mesh(const std::string& path, ObjCorners* corners = nullptr) {
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  ObjCorners ignored;
  std::string err;
  return read_mesh(path, &xyz, &faces, &err, corners ? corners : &ignored) ? "" : err;
}

// Whether anything opened `path` while `action` ran (inotify: exact, unlike access times).
template <class Action>
bool opened_during(const std::string& path, Action action) {
  const int fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
  if (fd < 0 || inotify_add_watch(fd, path.c_str(), IN_OPEN) < 0) {
    ADD_FAILURE() << "inotify on " << path << ": " << std::strerror(errno);
    return true;
  }
  action();
  char buf[4096];
  const bool opened = read(fd, buf, sizeof buf) > 0;
  close(fd);
  return opened;
}

// Runs `action` on a thread and waits at most `seconds`: a hang fails the test instead of
// stalling it (the thread is left behind; the test program ends soon after).
template <class Action>
bool finishes_within(double seconds, Action action) {
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> f = done->get_future();
  std::thread([done, action]() mutable {
    action();
    done->set_value();
  }).detach();
  return f.wait_for(std::chrono::duration<double>(seconds)) == std::future_status::ready;
}

TEST(HostileObj, MtllibIsKeptAsANameAndNeverOpened) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  write_bytes(dir / "outside.mtl", "newmtl a\nKd 1 0 0\n");
  for (const std::string& library : {std::string("../outside.mtl"), dir / "outside.mtl"}) {
    write_bytes(dir / "asset/m.obj", "mtllib " + library + "\n" + kTriangle + "usemtl a\nf 1 2 3\n");
    ObjCorners corners;
    std::string err = "not run";
    EXPECT_FALSE(opened_during(dir / "outside.mtl", [&] { err = read_obj_mesh(dir / "asset/m.obj", &corners); }))
        << library;
    EXPECT_EQ(err, "");
    EXPECT_EQ(corners.material_library, library);
  }
  // A FIFO would block a reader that opens it forever; /dev/zero would never end.
  ASSERT_EQ(mkfifo((dir / "asset/fifo.mtl").c_str(), 0600), 0);
  for (const std::string& library : {std::string("fifo.mtl"), std::string("/dev/zero")}) {
    write_bytes(dir / "asset/m.obj", "mtllib " + library + "\n" + kTriangle + "f 1 2 3\n");
    std::string err = "not run";
    EXPECT_TRUE(finishes_within(20, [&err, path = dir / "asset/m.obj"] { err = read_obj_mesh(path); })) << library;
    EXPECT_EQ(err, "") << library;
  }
}

TEST(HostileObj, ManyMaterialNamesAndLongFacesReadInLinearTime) {
  TempDir dir;
  // 300,000 names, each used by a face: a linear search per usemtl took minutes.
  std::string text = kTriangle;
  for (int m = 0; m < 300000; ++m) text += "usemtl m" + std::to_string(m) + "\nf 1 2 3\n";
  // One face of 200,000 corners naming a vertex twice at its end: a pairwise check is 2e10 steps.
  std::string polygon = "f";
  for (int v = 1; v <= 200000; ++v) polygon += " " + std::to_string(v);
  std::string big;
  for (int v = 0; v < 200000; ++v) big += "v " + std::to_string(v) + " " + std::to_string(v % 7) + " 0\n";
  write_bytes(dir / "names.obj", text);
  write_bytes(dir / "polygon.obj", big + polygon + " 1\n");
  ObjCorners corners;
  std::string names_err = "not run", polygon_err = "not run";
  ASSERT_TRUE(finishes_within(30, [&, path = dir / "names.obj"] { names_err = read_obj_mesh(path, &corners); }));
  EXPECT_EQ(names_err, "");
  EXPECT_EQ(corners.materials.size(), 300000u);
  ASSERT_TRUE(finishes_within(30, [&, path = dir / "polygon.obj"] { polygon_err = read_obj_mesh(path); }));
  EXPECT_TRUE(contains(polygon_err, "uses vertex 1 twice")) << polygon_err;
  // The same face without the repeat is read, triangulated, within the same bound.
  write_bytes(dir / "polygon.obj", big + polygon + "\n");
  ASSERT_TRUE(finishes_within(30, [&, path = dir / "polygon.obj"] { polygon_err = read_obj_mesh(path); }));
  EXPECT_EQ(polygon_err, "");
}

TEST(HostileObj, NamesKeepTheirSpacesAndUnusedNamesMakeNoGroup) {
  TempDir dir;
  write_bytes(dir / "m.obj", std::string("mtllib my materials.mtl\n") + kTriangle + "v 1 1 0\n" +
                                 "usemtl red paint\nf 1 2 3\nusemtl unused\nusemtl red glass  \nf 2 4 3\n");
  ObjCorners corners;
  ASSERT_EQ(read_obj_mesh(dir / "m.obj", &corners), "");
  EXPECT_EQ(corners.material_library, "my materials.mtl");
  EXPECT_EQ(corners.materials, (std::vector<std::string>{"red paint", "red glass"}));
  EXPECT_EQ(corners.face_material, (std::vector<int32_t>{0, 1}));
  Animation anim;
  std::vector<float> xyz;
  std::string err;
  ASSERT_TRUE(read_mesh(dir / "m.obj", &xyz, &anim.faces, &err)) << err;
  anim.vertex_count = 4;
  ASSERT_TRUE(obj_render(corners, &anim, &err)) << err;
  ASSERT_EQ(anim.render.groups.size(), 2u);  // no group for "unused", none without a material
  EXPECT_EQ(anim.render.groups[1].name, "red glass");
}

TEST(HostileObj, CommentsAfterRecordsAreComments) {
  TempDir dir;
  write_bytes(dir / "c.obj", "v 0 0 1e-50 # origin (below float's range: 0, as a stream reads it)\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1 #uv\n"
                             "f 1/1 2/2 3/3 # c\n# f 1 2 9\n");
  ObjCorners corners;
  ASSERT_EQ(read_obj_mesh(dir / "c.obj", &corners), "");
  EXPECT_EQ(corners.vertex, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_EQ(corners.texcoord, (std::vector<int64_t>{0, 1, 2}));
}

TEST(HostileObj, MalformedRecordsAreRefusedWithTheLine) {
  TempDir dir;
  const std::pair<std::string, std::string> cases[] = {
      {"usemtl caf\xe9\nf 1 2 3\n", "line 4: the material name is not UTF-8"},
      {"mtllib \xff\xfe.mtl\n", "line 4: the material library name is not UTF-8"},
      {"usemtl a\x01z\nf 1 2 3\n", "line 4: a control character"},
      {"f 1 2 4\n", "line 4: vertex index 4 out of range"},
      {"f 1/2 2/1 3/1\n", "texture coordinate index 2 out of range"},
      {"f 1//1 2 3\n", "normal index 1 out of range"},
      {"f 1/x 2 3\n", "face corner '1/x' is malformed"},
      {"f 1 2\n", "3 or more vertices"},
      {"vt 0x1p-1 0\n", "texture coordinates are not finite"},
      {"vn 0 0 nan\n", "normal values are not finite"},
  };
  for (const auto& [records, expected] : cases) {
    write_bytes(dir / "bad.obj", kTriangle + records);
    const std::string err = read_obj_mesh(dir / "bad.obj");
    EXPECT_TRUE(contains(err, dir / "bad.obj") && contains(err, expected)) << records << ": " << err;
  }
  write_bytes(dir / "bad.obj", "v 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_TRUE(contains(read_obj_mesh(dir / "bad.obj"), "line 1: vertex values are not finite"));
}

TEST(HostileObj, ReadingAFolderReportsReadingNotSimulating) {
  TempDir dir;
  fs::create_directories(dir / "in");
  for (int f = 0; f < 4; ++f) write_bytes(dir / ("in/frame_" + std::to_string(f) + ".obj"), std::string(kTriangle) + "f 1 2 3\n");
  EXPECT_EQ(input_stage_label(dir / "in"), "read");
  EXPECT_EQ(input_stage_label("cantilever"), "simulate");
  std::vector<double> reported;
  Animation anim;
  std::string err;
  ASSERT_TRUE(load_animation_input(dir / "in", false, [&](double x) { reported.push_back(x); }, &anim, &err)) << err;
  EXPECT_EQ(reported, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
}

// --- PC2 start frames -------------------------------------------------------------------

// A PC2 of one triangle, two frames, starting at frame `start`.
std::string pc2(float start) {
  std::string b(32, '\0');
  std::memcpy(&b[0], "POINTCACHE2", 12);
  const uint32_t version = 1, points = 3, frames = 2;
  const float rate = 1;
  std::memcpy(&b[12], &version, 4);
  std::memcpy(&b[16], &points, 4);
  std::memcpy(&b[20], &start, 4);
  std::memcpy(&b[24], &rate, 4);
  std::memcpy(&b[28], &frames, 4);
  const float xyz[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1};
  b.append(reinterpret_cast<const char*>(xyz), sizeof xyz);
  return b;
}

TEST(HostilePointCache, StartFramesMustGiveTimesThatOutputsCanHold) {
  TempDir dir;
  write_bytes(dir / "rest.obj", std::string(kTriangle) + "f 1 2 3\n");
  InputOptions options;
  options.rest_mesh = dir / "rest.obj";
  for (float start : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity(), 3e38f, -1e12f}) {
    write_bytes(dir / "c.pc2", pc2(start));
    Animation anim;
    std::string err;
    EXPECT_FALSE(load_animation_input(dir / "c.pc2", options, {}, &anim, &err)) << start;
    EXPECT_TRUE(contains(err, dir / "c.pc2") && contains(err, "the first frame's time")) << start << ": " << err;
  }
  write_bytes(dir / "c.pc2", pc2(12));
  Animation anim;
  std::string err;
  ASSERT_TRUE(load_animation_input(dir / "c.pc2", options, {}, &anim, &err)) << err;
  EXPECT_DOUBLE_EQ(anim.placement.start_time, 12.0 / anim.frame_rate);
}

// --- '+' in glTF uris -------------------------------------------------------------------

TEST(HostileGltfResources, PlusInAUriIsAPlus) {
  TempDir dir;
  write_triangle_buffer(dir / "a+b.bin");
  nlohmann::json j = triangle_gltf();
  Animation anim;
  std::string err;
  for (const char* uri : {"a+b.bin", "a%2Bb.bin"}) {
    j["buffers"][0]["uri"] = uri;
    std::ofstream(dir / "t.gltf") << j.dump();
    EXPECT_TRUE(read_gltf_animation(dir / "t.gltf", -1, &anim, &err)) << uri << ": " << err;
  }
  // "a b.bin" is another file, which tinygltf would ask for by the same name as "a+b.bin".
  write_triangle_buffer(dir / "a b.bin");
  j["buffers"][0]["uri"] = "a+b.bin";
  j["buffers"].push_back(j["buffers"][0]);
  j["buffers"][1]["uri"] = "a%20b.bin";
  j["bufferViews"][1]["buffer"] = 1;
  std::ofstream(dir / "t.gltf") << j.dump();
  EXPECT_FALSE(read_gltf_animation(dir / "t.gltf", -1, &anim, &err));
  EXPECT_TRUE(contains(err, "tinygltf reads as one")) << err;
}

}  // namespace hostile_obj
}  // namespace dcurve::test
