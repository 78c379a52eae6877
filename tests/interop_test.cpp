// Round trips through files written and read by independent tools: a .glb written by
// glTF-Transform goes in, and the .glb and .gltf that come out pass the Khronos validator and
// read back in glTF-Transform; PC2 and MDD files written by a few lines of Node go in, and
// the caches that come out read back in those lines. Every frame within the tolerance, with
// the right frame count, vertex order and face list.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "encoder/metrics.h"
#include "interop_util.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

constexpr double kTolerance = 1e-3;
// The error bound holds on the decoded floats; the independent readers add float sums
// (base + weight x target) of a few ulps on top.
constexpr double kFloatSlack = 1e-6;

class Interop : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found";
    const std::string why = interop_unavailable();
    if (!why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(interop_packages_present()) << "tests/interop/node_modules missing: run scripts/install-deps.sh";
    // Every tenth frame of cloth-sphere: 12 frames of 2,500 vertices, real motion.
    anim_ = read_corpus_frames("cloth-sphere", 12, 10);
    limit_ = kTolerance * bbox_diagonal(anim_.frames[0]) + kFloatSlack;
    ASSERT_TRUE(write_exchange(dir_ / "in.bin", anim_));
  }

  // With the exact index buffer kept, so every output must carry the input's face list.
  void encode(const std::string& input, const std::string& extra = "") {
    CommandResult r = run_cli("encode " + input + " -o " + dir_ / "x.dcrv --tolerance 1e-3 --grid 2 --low-rank off "
                              "--keep-face-order -q --force" + extra);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(r.output, "");  // -q: nothing on success
  }

  // The frame rate the encoded file records.
  double encoded_frame_rate() {
    CommandResult r = run_cli("info --json " + dir_ / "x.dcrv");
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(r.output)["frame_rate"].get<double>();
  }

  void expect_frames_within_tolerance(const Animation& back) {
    ASSERT_EQ(back.frames.size(), anim_.frames.size());
    ASSERT_EQ(back.vertex_count, anim_.vertex_count);
    EXPECT_LE(max_distance(anim_, back), limit_);
  }

  TempDir dir_;
  Animation anim_;
  double limit_ = 0;
};

TEST_F(Interop, GltfTransformGlbInValidatedGlbAndGltfOut) {
  CommandResult w = run_node("write_glb.mjs " + dir_ / "in.bin " + dir_ / "in.glb 24");
  ASSERT_EQ(w.exit_code, 0) << w.output;
  encode(dir_ / "in.glb");
  EXPECT_NEAR(encoded_frame_rate(), 24.0, 1e-3);
  for (const char* out : {"out.glb", "out.gltf"}) {
    CommandResult d = run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / out);
    ASSERT_EQ(d.exit_code, 0) << d.output;
    CommandResult v = run_node("validate.mjs " + dir_ / out);
    EXPECT_EQ(v.exit_code, 0) << out << ": " << v.output;
    EXPECT_NE(v.output.find("errors 0"), std::string::npos) << v.output;
    CommandResult r = run_node("read_glb.mjs " + dir_ / out + " " + dir_ / "back.bin");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find("keys 12 fps 24.000"), std::string::npos) << r.output;
    Animation back;
    ASSERT_TRUE(read_exchange(dir_ / "back.bin", &back));
    expect_frames_within_tolerance(back);
    EXPECT_EQ(back.faces, anim_.faces) << out;  // the face list as given, in its order
  }
  // --frames N: N keys over the same 11/24 s, so the clip keeps its duration.
  ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / "five.glb --frames 5").exit_code, 0);
  EXPECT_EQ(run_node("validate.mjs " + dir_ / "five.glb").exit_code, 0);
  CommandResult r = run_node("read_glb.mjs " + dir_ / "five.glb " + dir_ / "back.bin");
  EXPECT_NE(r.output.find("keys 5 fps 8.727"), std::string::npos) << r.output;
}

TEST_F(Interop, IndependentPc2AndMddInAndOut) {
  const std::string rest = corpus_ext("cloth-sphere/frame_00000.obj");
  for (const std::string kind : {"pc2", "mdd"}) {
    const std::string cache = dir_ / ("in." + kind);
    CommandResult w = run_node("point_cache.mjs write " + kind + " " + cache + " " + dir_ / "in.bin");
    ASSERT_EQ(w.exit_code, 0) << w.output;
    encode(cache, " --mesh " + rest);
    // MDD carries a time per frame (1/24 s apart); PC2 has no rate: 30 unless --fps.
    EXPECT_NEAR(encoded_frame_rate(), kind == "mdd" ? 24.0 : 30.0, 1e-3) << kind;
    for (const std::string out : {"pc2", "mdd"}) {
      const std::string decoded = dir_ / ("out." + out);
      CommandResult d = run_cli("decode " + dir_ / "x.dcrv -o " + decoded + " --force");
      ASSERT_EQ(d.exit_code, 0) << d.output;
      CommandResult r = run_node("point_cache.mjs read " + out + " " + decoded + " " + dir_ / "back.bin");
      ASSERT_EQ(r.exit_code, 0) << r.output;
      EXPECT_NE(r.output.find("frames 12 points 2500"), std::string::npos) << r.output;
      Animation back;
      ASSERT_TRUE(read_exchange(dir_ / "back.bin", &back));
      expect_frames_within_tolerance(back);
    }
    // The faces come from the rest mesh, as given.
    ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / (kind + ".obj") + " --t 0").exit_code, 0);
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string err;
    ASSERT_TRUE(read_mesh(dir_ / (kind + ".obj"), &xyz, &faces, &err)) << err;
    EXPECT_EQ(faces, anim_.faces);
  }
  CommandResult fps = run_cli("encode " + dir_ / "in.pc2 --mesh " + rest + " -o " + dir_ / "x.dcrv --grid 2 --low-rank off --fps 60 --force");
  ASSERT_EQ(fps.exit_code, 0) << fps.output;
  EXPECT_NEAR(encoded_frame_rate(), 60.0, 1e-9);
}

}  // namespace
}  // namespace dcurve::test
