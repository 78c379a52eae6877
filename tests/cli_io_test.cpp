// The CLI's inputs and outputs beyond frame folders: glTF inputs it refuses with a message
// naming the file (no weights animation, several meshes, non-triangles, unreadable sparse
// data, compression it does not decode), point caches that do not fit their mesh, frame
// folders in number order, and decode outputs: one mesh, --time, no stale frames, nothing
// left behind by a failure, memory that does not grow with --frames.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstring>
#include <fstream>

#include "cli_util.h"
#include "gltf_fixture.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "encoder/io/frames.h"
#include "test_util.h"

namespace dcurve::test {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

struct GltfCase {
  const char* name;
  void (*edit)(json&);
  const char* expected;  // in the message
};

const GltfCase kBadGltf[] = {
    {"no_animation", [](json& j) { j.erase("animations"); }, "has no animation of mesh 0's morph-target weights"},
    {"two_meshes", [](json& j) { j["meshes"].push_back(j["meshes"][0]); }, "holds 2 meshes (0 'tri', 1 'tri')"},
    {"lines", [](json& j) { j["meshes"][0]["primitives"][0]["mode"] = 1; }, "primitive is LINES, not TRIANGLES"},
    {"strip", [](json& j) { j["meshes"][0]["primitives"][0]["mode"] = 5; }, "TRIANGLE_STRIP, not TRIANGLES"},
    {"no_targets", [](json& j) { j["meshes"][0]["primitives"][0].erase("targets"); }, "has no morph targets"},
    // The sparse index read from the times' bytes (0.5f as u32): far past the 3 vertices.
    {"sparse_out_of_range",
     [](json& j) {
       j["accessors"][1]["sparse"] = {{"count", 1},
                                      {"indices", {{"bufferView", 3}, {"byteOffset", 4}, {"componentType", 5125}}},
                                      {"values", {{"bufferView", 1}}}};
     },
     "morph target 0: sparse index 1056964608 is out of range"},
    {"sparse_float_indices",
     [](json& j) {
       j["accessors"][1]["sparse"] = {{"count", 1},
                                      {"indices", {{"bufferView", 3}, {"componentType", 5126}}},
                                      {"values", {{"bufferView", 1}}}};
     },
     "sparse accessor with a count or index type dcurve cannot read"},
    {"draco",
     [](json& j) {
       j["extensionsUsed"] = {"KHR_draco_mesh_compression"};
       j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
     },
     "uses KHR_draco_mesh_compression, which dcurve does not decode"},
    {"meshopt", [](json& j) { j["extensionsUsed"] = {"EXT_meshopt_compression"}; },
     "uses EXT_meshopt_compression, which dcurve does not decode"},
};

TEST(CliIo, GltfFixtureEncodesAndOneMeshDecodes) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  std::ofstream(dir / "ok.gltf") << triangle_gltf().dump();
  CommandResult r = run_cli("encode " + dir / "ok.gltf -o " + dir / "ok.dcrv -v");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("dcurve encode: read 2 frames of 3 vertices, 1 triangles, 2.0"), std::string::npos) << r.output;
  // -o one.obj --t 0.5 writes that one file: halfway, z = 0.5.
  r = run_cli("decode " + dir / "ok.dcrv -o " + dir / "half.obj --t 0.5");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  ASSERT_TRUE(read_mesh(dir / "half.obj", &xyz, &faces, &err)) << err;
  for (int v = 0; v < 3; ++v) EXPECT_NEAR(xyz[3 * v + 2], 0.5, 2e-3);
  // --time in seconds: the clip is 0.5 s long, so 0.5 s is the last frame.
  ASSERT_EQ(run_cli("decode " + dir / "ok.dcrv -o " + dir / "end.ply --time 0.5").exit_code, 0);
  ASSERT_TRUE(read_mesh(dir / "end.ply", &xyz, &faces, &err)) << err;
  EXPECT_NEAR(xyz[2], 1.0, 2e-3);
  r = run_cli("decode " + dir / "ok.dcrv -o " + dir / "late.obj --time 0.6");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("past its end"), std::string::npos) << r.output;
  EXPECT_EQ(run_cli("decode " + dir / "ok.dcrv -o " + dir / "nan.obj --time nan").exit_code, 2);
  EXPECT_EQ(run_cli("decode " + dir / "ok.dcrv -o " + dir / "nan.obj --t nan").exit_code, 2);
  EXPECT_EQ(run_cli("encode " + dir / "ok.gltf -o " + dir / "nan.dcrv --fps nan").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "nan.obj") || fs::exists(dir / "nan.dcrv"));
  // One mesh needs a time.
  r = run_cli("decode " + dir / "ok.dcrv -o " + dir / "which.obj");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.output.find("--t"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "late.obj") || fs::exists(dir / "which.obj"));
}

TEST(CliIo, BadGltfIsRefusedNamingTheFile) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  for (const GltfCase& c : kBadGltf) {
    json j = triangle_gltf();
    c.edit(j);
    const std::string path = dir / (std::string(c.name) + ".gltf");
    std::ofstream(path) << j.dump();
    CommandResult r = run_cli("encode " + path + " -o " + dir / "out.dcrv");
    EXPECT_EQ(r.exit_code, 1) << c.name << ": " << r.output;
    EXPECT_EQ(r.output.rfind("dcurve encode: " + path + ": ", 0), 0u) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.name << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir / "out.dcrv")) << c.name;
  }
  // Several meshes: choose one.
  json j = triangle_gltf();
  j["meshes"].push_back(j["meshes"][0]);
  std::ofstream(dir / "two.gltf") << j.dump();
  EXPECT_EQ(run_cli("encode " + dir / "two.gltf --gltf-mesh 0 -o " + dir / "out.dcrv").exit_code, 0);
  CommandResult r = run_cli("encode " + dir / "two.gltf --gltf-mesh 2 -o " + dir / "out2.dcrv");
  EXPECT_NE(r.output.find("has no mesh 2"), std::string::npos) << r.output;
}

TEST(CliIo, SparseTargetIsApplied) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  // The target: zeros but for vertex 2, whose value is the 12 bytes at offset 24 of view 1
  // (0, 0, 1); its index is the third index (2) of view 2.
  j["accessors"][1].erase("bufferView");
  j["accessors"][1]["sparse"] = {{"count", 1},
                                 {"indices", {{"bufferView", 2}, {"byteOffset", 8}, {"componentType", 5125}}},
                                 {"values", {{"bufferView", 1}, {"byteOffset", 24}}}};
  std::ofstream(dir / "sparse.gltf") << j.dump();
  CommandResult r = run_cli("encode " + dir / "sparse.gltf -o " + dir / "s.dcrv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(run_cli("decode " + dir / "s.dcrv -o " + dir / "end.obj --t 1").exit_code, 0);
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  ASSERT_TRUE(read_mesh(dir / "end.obj", &xyz, &faces, &err)) << err;
  EXPECT_NEAR(xyz[2], 0.0, 2e-3);  // vertex 0 stays
  EXPECT_NEAR(xyz[8], 1.0, 2e-3);  // vertex 2 lifted by the sparse value
}

TEST(CliIo, NotGltfAtAllIsRefusedNamingTheFile) {
  TempDir dir;
  std::ofstream(dir / "junk.glb") << "not a glb";
  CommandResult r = run_cli("encode " + dir / "junk.glb -o " + dir / "out.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.output.rfind("dcurve encode: " + dir / "junk.glb: cannot read glTF", 0), 0u) << r.output;
}

TEST(CliIo, PointCacheThatDoesNotFitItsMeshIsRefused) {
  TempDir dir;
  write_triangle_obj(dir / "rest.obj", 0);
  std::ofstream(dir / "quad.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  // A PC2 of 3 vertices and 2 frames, and one cut short.
  std::vector<uint8_t> pc2(32 + 72, 0);
  std::memcpy(pc2.data(), "POINTCACHE2", 12);
  const uint32_t header[5] = {1, 3, 0, 0x3f800000, 2};
  std::memcpy(&pc2[12], header, 20);
  const float frames[18] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 0, 1, 1};
  std::memcpy(&pc2[32], frames, 72);
  std::string err;
  ASSERT_TRUE(write_file_atomic(dir / "c.pc2", pc2.data(), pc2.size(), &err));
  ASSERT_TRUE(write_file_atomic(dir / "cut.pc2", pc2.data(), pc2.size() - 5, &err));
  EXPECT_EQ(run_cli("encode " + dir / "c.pc2 --mesh " + dir / "rest.obj -o " + dir / "ok.dcrv").exit_code, 0);
  CommandResult r = run_cli("encode " + dir / "c.pc2 --mesh " + dir / "quad.obj -o " + dir / "out.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find(dir / "quad.obj: 4 vertices, but " + dir / "c.pc2 has 3"), std::string::npos) << r.output;
  r = run_cli("encode " + dir / "cut.pc2 --mesh " + dir / "rest.obj -o " + dir / "out.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find(dir / "cut.pc2: 99 bytes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("truncated"), std::string::npos) << r.output;
  r = run_cli("encode " + dir / "c.pc2 -o " + dir / "out.dcrv");
  EXPECT_NE(r.output.find("--mesh"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out.dcrv"));
}

// Every second frame of a DCC's output: the step sets the file's frame rate; --fps wins.
TEST(CliIo, FolderFrameStepSetsTheFrameRate) {
  TempDir dir;
  fs::create_directory(dir / "anim");
  for (int i = 0; i < 4; ++i) write_triangle_obj(dir / ("anim/frame_0000" + std::to_string(2 * i) + ".obj"), 0.1 * i);
  CommandResult r = run_cli("encode " + dir / "anim -o " + dir / "a.dcrv -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(run_cli("info " + dir / "a.dcrv").output.find("4 frames at 15 fps"), std::string::npos);
  r = run_cli("encode " + dir / "anim -o " + dir / "b.dcrv -q --fps 12");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(run_cli("info " + dir / "b.dcrv").output.find("4 frames at 12 fps"), std::string::npos);
  write_triangle_obj(dir / "anim/frame_00007.obj", 0.7);
  r = run_cli("encode " + dir / "anim -o " + dir / "c.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("frame_00006.obj and frame_00007.obj are 1 frame apart"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "c.dcrv"));
}

TEST(CliIo, FolderFramesInNumberOrderAndGapsNamed) {
  TempDir dir;
  fs::create_directory(dir / "anim");
  for (int i = 1; i <= 10; ++i) write_triangle_obj(dir / ("anim/anim." + std::to_string(i) + ".obj"), 0.1 * i);
  CommandResult r = run_cli("encode " + dir / "anim -o " + dir / "a.dcrv --fps 24 -q");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_EQ(run_cli("decode " + dir / "a.dcrv -o " + dir / "out").exit_code, 0);
  Animation back;
  std::string err;
  ASSERT_TRUE(read_frame_folder(dir / "out", &back, &err)) << err;
  ASSERT_EQ(back.frames.size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(back.frames[i][2], 0.1 * (i + 1), 2e-3) << "frame " << i;
  EXPECT_NE(run_cli("info " + dir / "a.dcrv").output.find("at 24 fps"), std::string::npos);
  fs::remove(dir / "anim/anim.5.obj");
  r = run_cli("encode " + dir / "anim -o " + dir / "b.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("frame 5 missing between anim.4.obj and anim.6.obj"), std::string::npos) << r.output;
  write_triangle_obj(dir / "anim/anim.5.obj", 0.5);
  write_triangle_obj(dir / "anim/anim.05.obj", 0.5);
  r = run_cli("encode " + dir / "anim -o " + dir / "b.dcrv");
  EXPECT_NE(r.output.find("anim.05.obj and anim.5.obj are both frame 5"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "b.dcrv"));
}

TEST(CliIo, FolderOutputIsNeverAStaleMix) {
  TempDir dir;
  fs::create_directory(dir / "anim");
  for (int i = 0; i < 6; ++i) write_triangle_obj(dir / ("anim/f" + std::to_string(i) + ".obj"), 0.1 * i);
  ASSERT_EQ(run_cli("encode " + dir / "anim -o " + dir / "a.dcrv --chunk-frames 2").exit_code, 0);
  ASSERT_EQ(run_cli("decode " + dir / "a.dcrv -o " + dir / "out").exit_code, 0);
  EXPECT_EQ(listing(dir / "out").size(), 6u);
  CommandResult r = run_cli("decode " + dir / "a.dcrv -o " + dir / "out --frames 3");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("already holds frames (frame_00000.obj, ...)"), std::string::npos) << r.output;
  EXPECT_EQ(listing(dir / "out").size(), 6u);
  ASSERT_EQ(run_cli("decode " + dir / "a.dcrv -o " + dir / "out --frames 3 --force").exit_code, 0);
  EXPECT_EQ(listing(dir / "out"), (std::vector<std::string>{"frame_00000.obj", "frame_00001.obj", "frame_00002.obj"}));
  // A chunk damaged on disk fails the decode part-way: nothing is left, in the output or beside it.
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(read_file(dir / "a.dcrv", &bytes, &err));
  bytes[bytes.size() - 2] ^= 0x40;
  ASSERT_TRUE(write_file_atomic(dir / "bad.dcrv", bytes.data(), bytes.size(), &err));
  const auto before = listing(dir.path.string());
  for (const char* out : {"fresh", "fresh.pc2", "fresh.glb"}) {
    r = run_cli("decode " + dir / "bad.dcrv -o " + dir / out);
    EXPECT_EQ(r.exit_code, 1) << out << ": " << r.output;
    EXPECT_EQ(r.output.rfind("dcurve decode: ", 0), 0u) << r.output;
    EXPECT_EQ(listing(dir.path.string()), before) << out;
  }
  r = run_cli("decode " + dir / "bad.dcrv -o " + dir / "out --force");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(listing(dir / "out").size(), 3u);  // the previous frames, untouched
}

TEST(CliIo, ManyFramesStreamOrAreRefusedUpFront) {
  TempDir dir;
  fs::create_directory(dir / "anim");
  for (int i = 0; i < 3; ++i) write_triangle_obj(dir / ("anim/f" + std::to_string(i) + ".obj"), 0.1 * i);
  ASSERT_EQ(run_cli("encode " + dir / "anim -o " + dir / "a.dcrv").exit_code, 0);
  // glTF holds every frame as a target and weights growing with frames squared: refused
  // before decoding rather than running out of memory.
  CommandResult r = run_cli("decode " + dir / "a.dcrv -o " + dir / "many.glb --frames 1000000");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("more than the 1024 MiB dcurve writes"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "many.glb"));
  // A point cache streams: a million frames of a triangle, one frame in memory at a time.
  r = run_cli("decode " + dir / "a.dcrv -o " + dir / "many.pc2 --frames 1000000");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(fs::file_size(dir / "many.pc2"), 32u + 1000000u * 36u);
}

TEST(CliIo, OutputFolderIsCheckedBeforeTheWork) {
  TempDir dir;
  fs::create_directory(dir / "anim");
  for (int i = 0; i < 2; ++i) write_triangle_obj(dir / ("anim/f" + std::to_string(i) + ".obj"), 0.1 * i);
  CommandResult r = run_cli("encode " + dir / "anim -o " + dir / "nowhere/a.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("nowhere/a.dcrv: folder"), std::string::npos) << r.output;
  r = run_cli("encode " + dir / "anim -o " + dir / "anim");
  EXPECT_NE(r.output.find("is a folder"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace dcurve::test
