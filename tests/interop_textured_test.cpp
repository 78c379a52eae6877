// A textured cloth as glTF-Transform writes it (tests/interop/write_textured_glb.mjs: a UV
// seam, normals, the mesh node inside a scaled parent, keys from 1/24 s, an object animation
// beside the morph animation) through encode and decode: the .glb that comes out passes the
// Khronos validator, and glTF-Transform reads back the UVs within their precision, seam
// copies at distance 0 with one normal in every frame, the node's world transform, the first
// key time and the names. The dropped object animation is named to the user.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "interop_util.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

using Json = nlohmann::json;

Json read_glb(const std::string& path) {
  CommandResult r = run_node("read_textured_glb.mjs " + path);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return r.exit_code == 0 ? Json::parse(r.output) : Json();
}

double diagonal(const std::vector<double>& xyz) {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) + (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

class InteropTextured : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string why = interop_unavailable();
    if (!why.empty()) GTEST_SKIP() << why;
    ASSERT_TRUE(interop_packages_present()) << "tests/interop/node_modules missing: run scripts/install-deps.sh";
    CommandResult w = run_node("write_textured_glb.mjs " + dir_ / "in.glb");
    ASSERT_EQ(w.exit_code, 0) << w.output;
    layout_ = Json::parse(w.output);
    CommandResult e = run_cli("encode " + dir_ / "in.glb -o " + dir_ / "x.dcrv --tolerance 1e-3 --force");
    ASSERT_EQ(e.exit_code, 0) << e.output;
    encode_output_ = e.output;
    in_ = read_glb(dir_ / "in.glb");
  }

  TempDir dir_;
  Json layout_, in_;
  std::string encode_output_;
};

TEST_F(InteropTextured, SeamsUvsPlacementAndStartTimeComeBackInAValidGlb) {
  EXPECT_TRUE(contains(encode_output_, "animation 'walk' (translation of node 'rig') is not stored")) << encode_output_;
  ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / "out.glb").exit_code, 0);
  CommandResult v = run_node("validate.mjs " + dir_ / "out.glb");
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_TRUE(contains(v.output, "errors 0")) << v.output;
  const Json out = read_glb(dir_ / "out.glb");
  ASSERT_FALSE(out.is_null());

  // Render vertices in the input's order, with their UVs within 14 bits of the range [0, 1].
  ASSERT_EQ(out["vertices"], in_["vertices"]);
  const std::vector<double> uv_in = in_["uv"], uv_out = out["uv"];
  ASSERT_EQ(uv_in.size(), uv_out.size());
  for (size_t i = 0; i < uv_in.size(); ++i) EXPECT_NEAR(uv_out[i], uv_in[i], 1.0 / (2 * 16383) + 1e-6) << i;

  // Every frame within the tolerance; each seam pair at distance 0 with one normal.
  const std::vector<std::vector<double>> p_in = in_["positions"], p_out = out["positions"], n_out = out["normals"];
  ASSERT_EQ(p_in.size(), p_out.size());
  ASSERT_EQ(n_out.size(), p_out.size());
  const double limit = 1e-3 * diagonal(p_in[0]) + 1e-6;
  const uint32_t columns = layout_["columns"], rows = layout_["rows"], around = layout_["around"];
  for (size_t f = 0; f < p_out.size(); ++f) {
    for (size_t i = 0; i < p_in[f].size(); i += 3)
      EXPECT_LE(std::hypot(p_out[f][i] - p_in[f][i], p_out[f][i + 1] - p_in[f][i + 1], p_out[f][i + 2] - p_in[f][i + 2]),
                limit);
    for (uint32_t j = 0; j < rows; ++j)
      for (int k = 0; k < 3; ++k) {
        const size_t first = 3 * size_t(j * columns) + k, copy = 3 * size_t(j * columns + around) + k;
        EXPECT_EQ(p_out[f][first], p_out[f][copy]) << "frame " << f << " row " << j;
        EXPECT_EQ(n_out[f][first], n_out[f][copy]) << "frame " << f << " row " << j;
      }
  }

  // Placement and timing: the world transform (parent scale 2, translation 1.2 up), the
  // first key at 1/24 s, the names.
  const std::vector<double> m_in = in_["worldMatrix"], m_out = out["worldMatrix"];
  ASSERT_EQ(m_out.size(), 16u);
  for (int i = 0; i < 16; ++i) EXPECT_NEAR(m_out[i], m_in[i], 1e-12) << i;
  EXPECT_NEAR(m_out[13], 2.4, 1e-6);
  EXPECT_NEAR(out["times"][0].get<double>(), layout_["firstTime"].get<double>(), 1e-7);
  EXPECT_NEAR(out["times"].back().get<double>(), in_["times"].back().get<double>(), 1e-6);
  EXPECT_EQ(out["nodeName"], "cloth");
  EXPECT_EQ(out["meshName"], "tube");
}

TEST_F(InteropTextured, PointCachesStartAtTheInputsFirstFrame) {
  // 1/24 s at 24 fps: PC2's start frame 1, MDD's first time 1/24 s.
  ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / "out.pc2").exit_code, 0);
  ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / "out.mdd").exit_code, 0);
  std::ifstream pc2(dir_ / "out.pc2", std::ios::binary), mdd(dir_ / "out.mdd", std::ios::binary);
  char header[32];
  ASSERT_TRUE(pc2.read(header, 32));
  float start;
  std::memcpy(&start, header + 20, 4);
  EXPECT_NEAR(start, 1.0f, 1e-5f);
  uint32_t points;
  std::memcpy(&points, header + 16, 4);
  EXPECT_EQ(points, 144u);  // a point cache holds one position per vertex: 153 render vertices, 9 seam copies
  unsigned char m[12];
  ASSERT_TRUE(mdd.read(reinterpret_cast<char*>(m), 12));
  const uint32_t bits = uint32_t(m[8]) << 24 | uint32_t(m[9]) << 16 | uint32_t(m[10]) << 8 | m[11];
  float first;
  std::memcpy(&first, &bits, 4);
  EXPECT_NEAR(first, 1.0f / 24, 1e-6f);
}

}  // namespace
}  // namespace dcurve::test
