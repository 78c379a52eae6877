// Hostile input at the library level (issue 59, decode and output side): what REND, PLAC and
// MATL carry into glTF and OBJ outputs (nesting, names, placeholders, empty and many groups,
// invalid UTF-8), attribute ranges at the ends of binary32, names past the format's limit,
// images that compress too well or not at all. Each input is made here.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "decoder/dcurve.h"
#include "decoder/dcurve.hpp"
#include "encoder/encoder.h"
#include "encoder/io/files.h"
#include "encoder/io/gltf_writer.h"
#include "encoder/io/mesh_writer.h"
#include "encoder/io/output_file.h"
#include "test_util.h"

namespace dcurve::test {
namespace {
using nlohmann::json;

// A 4 x 4 sheet (16 vertices, 18 triangles) over `frames` frames, each vertex its own render
// vertex with a UV, the triangles in `groups` groups of material g (group g: triangles t with
// t % groups == g).
Animation sheet(uint32_t frames, uint32_t groups = 0) {
  Animation a;
  a.vertex_count = 16;
  a.faces = grid_faces(4, 4);
  for (uint32_t f = 0; f < frames; ++f) {
    a.frames.emplace_back();
    for (uint32_t v = 0; v < 16; ++v) a.frames.back().insert(a.frames.back().end(), {float(v % 4), float(v / 4), 0.1f * f * (v % 3)});
  }
  AnimationRender& r = a.render;
  AnimationRender::Attribute uv{AttributeSemantic::TexCoord0, 2, {}};
  for (uint32_t v = 0; v < 16; ++v) {
    r.source.push_back(v);
    uv.values.insert(uv.values.end(), {float(v % 4) / 3, float(v / 4) / 3});
  }
  r.corners = a.faces;
  r.attributes = {uv};
  for (uint32_t g = 0; g < groups; ++g) r.groups.push_back({int32_t(g), "m" + std::to_string(g)});
  if (groups > 0)
    for (uint32_t t = 0; t < a.faces.size() / 3; ++t) r.face_group.push_back(t % groups);
  return a;
}

std::unique_ptr<Decoder> open_encoded(const Animation& anim, std::vector<uint8_t>* bytes) {
  *bytes = encoded(anim, EncodeOptions());
  std::string err;
  auto dec = Decoder::open_memory(bytes->data(), bytes->size(), &err);
  EXPECT_TRUE(dec) << err;
  return dec;
}

// Writes frames of 16 vertices (a 4 x 4 sheet moving up) as glTF with `scene`; the error, or "".
std::string write_gltf(const std::string& path, const std::vector<uint32_t>& faces, uint32_t frames,
                       const GltfScene& scene) {
  GltfWriter writer(16, faces, frames, 24, true, scene);
  std::string err;
  if (!writer.open(path, false, &err)) return err;
  for (uint32_t f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (uint32_t v = 0; v < 16; ++v) xyz.insert(xyz.end(), {float(v % 4), float(v / 4), 0.1f * f});
    if (!writer.add_frame(xyz.data(), &err)) return err;
  }
  return writer.finish(&err) ? "" : err;
}

// The JSON chunk of a .glb, parsed (which also checks it is UTF-8).
json glb_json(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  uint32_t length = 0;
  if (bytes.size() < 20) return json();
  std::memcpy(&length, bytes.data() + 12, 4);
  return json::parse(bytes.substr(20, length));
}

// Whether every accessor is an object with a positive count and every index a primitive
// names exists.
::testing::AssertionResult accessors_intact(const json& doc) {
  const size_t accessors = doc["accessors"].size();
  for (const json& a : doc["accessors"])
    if (!a.is_object() || !(a.value("count", 0) > 0)) return ::testing::AssertionFailure() << "accessor " << a.dump();
  for (const json& p : doc["meshes"][0]["primitives"]) {
    if (p.contains("indices") && p["indices"].get<size_t>() >= accessors) return ::testing::AssertionFailure() << p.dump();
    for (const json& t : p.value("targets", json::array()))
      if (!t.is_object() || t["POSITION"].get<size_t>() >= accessors) return ::testing::AssertionFailure() << p.dump();
  }
  return ::testing::AssertionSuccess();
}

// --- 1. MATL's JSON nested past any glTF ---------------------------------------------------

TEST(HostileRender, DeeplyNestedMaterialsAreRefusedByTheGltfWriter) {
  TempDir dir;
  GltfScene scene;
  scene.materials_json = "{\"materials\":[{\"extras\":" + std::string(100000, '[') + std::string(100000, ']') + "}]}";
  const std::string err = write_gltf(dir / "o.glb", grid_faces(4, 4), 3, scene);
  EXPECT_TRUE(contains(err, "nested deeper than 128")) << err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.glb"));
}

// --- 2. Many face groups: one pass over the JSON ------------------------------------------

TEST(HostileRender, ManyFaceGroupsWriteGltfInLinearTime) {
  TempDir dir;
  constexpr uint32_t kGroups = 100000;
  std::vector<uint32_t> faces;
  GltfScene scene;
  for (uint32_t g = 0; g < kGroups; ++g) {
    faces.insert(faces.end(), {g % 12, g % 12 + 1, g % 12 + 4});
    scene.group_faces.push_back(1);
    scene.group_materials.push_back(-1);
  }
  const std::clock_t start = std::clock();
  ASSERT_EQ(write_gltf(dir / "o.glb", faces, 3, scene), "");
  const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_LT(seconds, 20.0);  // 2.4 s; splicing the targets into each primitive took 60 s
  const json doc = glb_json(dir / "o.glb");
  ASSERT_EQ(doc["meshes"][0]["primitives"].size(), kGroups);
  EXPECT_EQ(doc["meshes"][0]["primitives"][kGroups - 1]["targets"].size(), 2u);
  EXPECT_TRUE(accessors_intact(doc));
}

// --- 3. Names in OBJ output stay on their lines -------------------------------------------

TEST(HostileRender, ObjNamesCannotInjectRecords) {
  ObjRender r;
  for (uint32_t v = 0; v < 16; ++v) r.source.push_back(v);
  r.corners = grid_faces(4, 4);
  r.group_faces = {9, 9};
  r.group_names = {"a\nv 9 9 9\nmtllib evil.mtl", "b\r\nf 1 1 1"};
  r.material_library = "lib.mtl\nv 1 1 1";
  std::vector<float> xyz(48, 0.5f);
  std::string text;
  obj_render_bytes(xyz.data(), 16, r, nullptr, &text);
  size_t v = 0, f = 0, mtllib = 0, usemtl = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    v += line.rfind("v ", 0) == 0;
    f += line.rfind("f ", 0) == 0;
    mtllib += line.rfind("mtllib", 0) == 0;
    usemtl += line.rfind("usemtl", 0) == 0;
  }
  EXPECT_EQ(v, 16u);  // a vertex more would shift every face index
  EXPECT_EQ(f, 18u);
  EXPECT_EQ(mtllib, 1u);
  EXPECT_EQ(usemtl, 2u);
  EXPECT_TRUE(contains(text, "mtllib lib.mtl\\x0av 1 1 1\n")) << text;
  EXPECT_TRUE(contains(text, "usemtl b\\x0d\\x0af 1 1 1\n")) << text;
}

// --- 4. Materials that spell the writer's placeholders ------------------------------------

TEST(HostileRender, MaterialsThatSpellTheWritersMarksLeaveAccessorsIntact) {
  TempDir dir;
  const json extras = {{"accessors", {"dcurve-morph-targets"}},
                       {"targets", {"dcurve-morph-targets"}},
                       {"min", {-2.2250738585072014e-308}}};
  GltfScene scene;
  scene.materials_json = json({{"materials", {{{"name", "dcurve-morph-targets"}, {"extras", extras}}}}}).dump();
  scene.group_faces = {18};
  scene.group_materials = {0};
  ASSERT_EQ(write_gltf(dir / "o.glb", grid_faces(4, 4), 3, scene), "");
  const json doc = glb_json(dir / "o.glb");
  EXPECT_TRUE(accessors_intact(doc));
  EXPECT_EQ(doc["materials"][0]["extras"], extras);  // as stored, nothing spliced into it
  EXPECT_EQ(doc["meshes"][0]["primitives"][0]["targets"].size(), 2u);
}

// --- 5. Attribute ranges at the ends of binary32 ------------------------------------------

TEST(HostileRender, UvsSpanningTheFloatRangeDecodeFiniteWithinTheirError) {
  Animation a = sheet(2);
  std::vector<float>& uv = a.render.attributes[0].values;
  for (size_t i = 0; i < uv.size(); ++i) uv[i] = (i % 4 < 2 ? -3e38f : 3e38f) * (i % 3 == 0 ? 1.f : 0.5f);
  std::vector<uint8_t> bytes;
  auto dec = open_encoded(a, &bytes);
  ASSERT_TRUE(dec);
  const float* decoded = dec->attribute(Attribute::TexCoord0);
  ASSERT_NE(decoded, nullptr);
  dcurve_decoder* c = nullptr;
  ASSERT_EQ(dcurve_open_memory(bytes.data(), bytes.size(), &c, nullptr, 0), DCURVE_OK);
  const float* through_c = dcurve_attribute(c, DCURVE_ATTRIBUTE_TEXCOORD_0);
  // (hi - lo) / (2 (2^14 - 1)) for a range of 6e38, plus binary32 rounding.
  const double bound = 6e38 / (2 * 16383.0) * 1.001;
  for (size_t i = 0; i < uv.size(); ++i) {
    ASSERT_TRUE(std::isfinite(decoded[i])) << i;
    EXPECT_LE(std::fabs(double(decoded[i]) - uv[i]), bound) << i;
    EXPECT_EQ(through_c[i], decoded[i]) << i;
  }
  dcurve_close(c);
}

// --- 6. Empty face groups -----------------------------------------------------------------

TEST(HostileRender, EmptyFaceGroupsGetNoPrimitive) {
  TempDir dir;
  GltfScene scene;
  scene.materials_json = R"({"materials":[{"name":"a"},{"name":"b"},{"name":"c"}]})";
  scene.group_faces = {0, 10, 0, 8};  // consecutive usemtl lines, and one at the start
  scene.group_materials = {0, 1, 2, 0};
  ASSERT_EQ(write_gltf(dir / "o.glb", grid_faces(4, 4), 2, scene), "");
  const json doc = glb_json(dir / "o.glb");
  const json& primitives = doc["meshes"][0]["primitives"];
  ASSERT_EQ(primitives.size(), 2u);
  EXPECT_EQ(primitives[0]["material"], 1);
  EXPECT_EQ(primitives[1]["material"], 0);
  EXPECT_EQ(doc["accessors"][primitives[1]["indices"].get<size_t>()]["byteOffset"], 120);  // after 10 triangles
  EXPECT_TRUE(accessors_intact(doc));
}

// --- 7. Names past the format's limit -----------------------------------------------------

TEST(HostileRender, OverlongNamesAreRefusedBeforeEncoding) {
  Animation a = sheet(2, 2);
  a.render.groups[1].name = "long" + std::string(2000, 'x');
  std::vector<uint8_t> bytes;
  std::string err;
  EXPECT_FALSE(encode_animation(a, EncodeOptions(), &bytes, nullptr, &err));
  EXPECT_TRUE(contains(err, "material name \"longxxx")) << err;
  EXPECT_TRUE(contains(err, "2004 bytes, more than the 1024")) << err;
  EXPECT_LT(err.size(), 400u) << err;  // the name is cut
  Animation b = sheet(2);
  b.placement.node_name = std::string(1025, 'n');
  EXPECT_FALSE(encode_animation(b, EncodeOptions(), &bytes, nullptr, &err));
  EXPECT_TRUE(contains(err, "node name \"nnn")) << err;
  b.placement.node_name = std::string(1024, 'n');  // at the limit: kept
  ASSERT_TRUE(encode_animation(b, EncodeOptions(), &bytes, nullptr, &err)) << err;
}

// --- 8. and 12. Images that compress too well, or not at all ------------------------------

Animation textured_sheet(std::vector<uint8_t> image) {
  Animation a = sheet(2, 1);
  a.materials.json = R"({"materials":[{"name":"m0"}],"images":[{"mimeType":"image/png"}]})";
  a.materials.images = {{"image/png", std::move(image)}};
  return a;
}

TEST(HostileRender, ACompressibleTextureOverAMebibyteReadsBack) {
  std::vector<uint8_t> image(size_t(3) << 20, 0);
  image[12345] = 7;
  std::vector<uint8_t> bytes;
  auto dec = open_encoded(textured_sheet(image), &bytes);
  ASSERT_TRUE(dec);
  size_t size = 0;
  const uint8_t* back = dec->image(0, &size);
  ASSERT_EQ(size, image.size());
  EXPECT_EQ(std::memcmp(back, image.data(), size), 0);
}

TEST(HostileRender, IncompressibleImageBytesAreNotSearchedAtLevel19) {
  std::vector<uint8_t> image(size_t(16) << 20);
  std::mt19937 random(59);
  for (uint8_t& b : image) b = uint8_t(random());
  const std::clock_t start = std::clock();  // processor time: other builds on the machine do not count
  std::vector<uint8_t> bytes = encoded(textured_sheet(image), EncodeOptions());
  const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
  EXPECT_LT(seconds, 2.0);  // level 19 took 5 s over these 16 MiB, level 3 0.1 s
  EXPECT_LT(bytes.size(), image.size() + 4096);
}

// --- 9. Names that are not UTF-8 ----------------------------------------------------------

TEST(HostileRender, NamesThatAreNotUtf8WriteValidGltf) {
  TempDir dir;
  GltfScene scene;
  scene.placement.mesh_name = "mesh\xff\nline";
  scene.placement.node_name = "\xc3";
  scene.materials_json = R"({"materials":[{"name":"a"}],"images":[{"name":"i"}]})";
  scene.images = {{"image/\xfe", {1, 2, 3}}};
  ASSERT_EQ(write_gltf(dir / "o.glb", grid_faces(4, 4), 2, scene), "");
  const json doc = glb_json(dir / "o.glb");  // parsing checks the UTF-8
  EXPECT_EQ(doc["meshes"][0]["name"], "mesh\xef\xbf\xbd\nline");  // U+FFFD; the newline escaped by JSON
  EXPECT_EQ(doc["nodes"][0]["name"], "\xef\xbf\xbd");
  EXPECT_EQ(doc["images"][0]["mimeType"], "image/\xef\xbf\xbd");
}

// --- 13. The decoder fuzz target's seeds --------------------------------------------------

// The seeds scripts/fuzz.sh gives the decoder fuzz target besides the test vectors: REND
// with attributes and groups, PLAC, MATL with an image, in formats 3 and 4. Rewritten with
// DCURVE_WRITE_FUZZ_SEEDS=1; otherwise checked to hold those sections.
TEST(HostileRender, DecoderFuzzSeedsHoldRenderPlacementAndMaterials) {
  Animation a = textured_sheet({0x89, 'P', 'N', 'G', 13, 10, 26, 10});
  a.render.groups.push_back({-1, "none"});
  for (uint32_t t = 0; t < a.render.face_group.size(); t += 4) a.render.face_group[t] = 1;
  a.render.attributes.push_back({AttributeSemantic::Color0, 4, std::vector<float>(64, 0.5f)});
  a.placement = {0.5, true, {2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 1, 2, 3, 1}, "mesh", "node"};
  const std::string folder = std::string(DCURVE_SOURCE_DIR) + "/tests/fuzz/decoder_seeds/";
  for (Profile profile : {Profile::Small, Profile::Fast}) {
    const std::string path = folder + (profile == Profile::Fast ? "render_fast.dcrv" : "render_small.dcrv");
    std::string err;
    std::vector<uint8_t> bytes;
    if (std::getenv("DCURVE_WRITE_FUZZ_SEEDS")) {
      EncodeOptions o;
      o.profile = profile;
      bytes = encoded(a, o);
      ASSERT_TRUE(write_file_atomic(path, bytes.data(), bytes.size(), &err)) << err;
    }
    ASSERT_TRUE(read_file(path, &bytes, &err)) << err;
    auto dec = Decoder::open_memory(bytes.data(), bytes.size(), &err);
    ASSERT_TRUE(dec) << path << ": " << err;
    EXPECT_EQ(dec->group_count(), 2u) << path;
    EXPECT_EQ(dec->image_count(), 1u) << path;
    EXPECT_NE(dec->colors(), nullptr) << path;
    EXPECT_EQ(dec->node_name(), "node") << path;
  }
}

}  // namespace
}  // namespace dcurve::test
