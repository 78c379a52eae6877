// glTF in and out at the library level (so the sanitizer pass runs them): the hand-written
// fixture reads as its two frames, the writer's .glb and .gltf read back as the frames
// written, and malformed offsets, counts and indices are refused, never read out of bounds.
#include <gtest/gtest.h>

#include <fstream>

#include "encoder/io/gltf_reader.h"
#include "encoder/io/gltf_writer.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace dcurve::test {
namespace {
using nlohmann::json;

// Writes the fixture with one edit and reads it; the message when refused.
std::string read_edited(const TempDir& dir, void (*edit)(json&), Animation* anim) {
  json j = triangle_gltf();
  edit(j);
  std::ofstream(dir / "t.gltf") << j.dump();
  std::string err;
  return read_gltf_animation(dir / "t.gltf", -1, anim, &err) ? "" : err;
}

TEST(GltfIo, FixtureReadsAsItsKeys) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  Animation anim;
  ASSERT_EQ(read_edited(dir, [](json&) {}, &anim), "");
  ASSERT_EQ(anim.frames.size(), 2u);
  EXPECT_EQ(anim.vertex_count, 3u);
  EXPECT_EQ(anim.faces, (std::vector<uint32_t>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(anim.frame_rate, 2.0);  // keys 0.5 s apart
  EXPECT_EQ(anim.frames[0], (std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0}));
  EXPECT_EQ(anim.frames[1], (std::vector<float>{0, 0, 1, 1, 0, 1, 0, 1, 1}));
}

TEST(GltfIo, WrittenFramesReadBack) {
  TempDir dir;
  Animation anim;
  anim.vertex_count = 16;
  anim.faces = grid_faces(4, 4);
  anim.frame_rate = 12;
  for (int f = 0; f < 5; ++f) {
    anim.frames.emplace_back();
    for (int v = 0; v < 16; ++v) anim.frames.back().insert(anim.frames.back().end(), {float(v % 4), float(v / 4), 0.1f * f * v});
  }
  for (const char* name : {"w.glb", "w.gltf"}) {
    const bool binary = std::string(name) == "w.glb";
    GltfWriter writer(anim.vertex_count, anim.faces, uint32_t(anim.frames.size()), anim.frame_rate, binary);
    std::string err;
    ASSERT_TRUE(writer.open(dir / name, false, &err)) << err;
    for (const auto& frame : anim.frames) ASSERT_TRUE(writer.add_frame(frame.data(), &err)) << err;
    ASSERT_TRUE(writer.finish(&err)) << err;
    Animation back;
    ASSERT_TRUE(read_gltf_animation(dir / name, -1, &back, &err)) << err;
    ASSERT_EQ(back.frames.size(), anim.frames.size()) << name;
    EXPECT_EQ(back.faces, anim.faces) << name;
    EXPECT_NEAR(back.frame_rate, 12.0, 1e-4) << name;
    for (size_t f = 0; f < anim.frames.size(); ++f)
      for (size_t i = 0; i < anim.frames[f].size(); ++i)
        EXPECT_NEAR(back.frames[f][i], anim.frames[f][i], 1e-6) << name << " frame " << f;
  }
}

TEST(GltfIo, MalformedOffsetsCountsAndIndicesAreRefused) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  const std::pair<void (*)(json&), const char*> cases[] = {
      {[](json& j) { j["accessors"][0]["count"] = 1000000000000LL; }, "POSITION"},
      {[](json& j) { j["accessors"][0]["byteOffset"] = 4; }, "runs past the end"},
      {[](json& j) { j["bufferViews"][1]["byteOffset"] = 96; }, "runs past the end"},
      {[](json& j) { j["bufferViews"][0]["byteStride"] = 400; }, ""},
      {[](json& j) { j["accessors"][2]["count"] = 2; }, "not a multiple of 3"},
      {[](json& j) { j["meshes"][0]["primitives"][0]["indices"] = 4; }, "indices"},
      {[](json& j) { j["meshes"][0]["primitives"][0]["indices"] = 9; }, ""},
      {[](json& j) { j["accessors"][4]["count"] = 1; }, "values for 2 keys"},
      {[](json& j) { j["animations"][0]["channels"][0]["sampler"] = 3; }, ""},
      {[](json& j) { j["accessors"][1]["type"] = "VEC2"; }, "morph target 0"},
      {[](json& j) {
         j["accessors"][1]["sparse"] = {{"count", 1000000},
                                        {"indices", {{"bufferView", 2}, {"componentType", 5125}}},
                                        {"values", {{"bufferView", 1}}}};
       },
       "sparse"},
  };
  for (const auto& [edit, expected] : cases) {
    Animation anim;
    const std::string err = read_edited(dir, edit, &anim);
    EXPECT_NE(err, "") << expected;
    EXPECT_EQ(err.rfind(dir / "t.gltf: ", 0), 0u) << err;
    EXPECT_NE(err.find(expected), std::string::npos) << err;
  }
}

TEST(GltfIo, IndexOutOfRangeIsRefused) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  // Indices read from the target's bytes (floats 0, 0, 1.0f): 1.0f as u32 is far past 3 vertices.
  Animation anim;
  const std::string err = read_edited(dir, [](json& j) { j["accessors"][2]["bufferView"] = 1; }, &anim);
  EXPECT_NE(err.find("indices: vertex 1065353216 does not exist"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve::test
