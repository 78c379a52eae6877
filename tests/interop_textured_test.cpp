// A textured cloth as glTF-Transform writes it (tests/interop/write_textured_glb.mjs: two
// primitives with two materials, one textured; a UV seam; normals; the mesh node inside a
// scaled parent; keys from 1/24 s; an object animation beside the morph animation) through
// encode and decode: the .glb that comes out passes the Khronos validator, and glTF-Transform
// reads back both materials and the texture's bytes, the UVs within their precision, seam
// copies at distance 0 with one normal in every frame, the node's world transform, the first
// key time and the names. The dropped object animation is named to the user.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
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

// The input's primitives' arrays one after the other: the render vertices' order.
std::vector<double> joined(const Json& primitives, const char* key, size_t frame = SIZE_MAX) {
  std::vector<double> out;
  for (const Json& p : primitives) {
    const Json& values = frame == SIZE_MAX ? p[key] : p[key][frame];
    for (const Json& x : values) out.push_back(x.get<double>());
  }
  return out;
}

TEST_F(InteropTextured, SeamsUvsMaterialsPlacementAndStartTimeComeBackInAValidGlb) {
  EXPECT_TRUE(contains(encode_output_, "animation 'walk' (translation of node 'rig') is not stored")) << encode_output_;
  ASSERT_EQ(run_cli("decode " + dir_ / "x.dcrv -o " + dir_ / "out.glb").exit_code, 0);
  CommandResult v = run_node("validate.mjs " + dir_ / "out.glb");
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_TRUE(contains(v.output, "errors 0")) << v.output;
  const Json out = read_glb(dir_ / "out.glb");
  ASSERT_FALSE(out.is_null());
  const Json& in_prims = in_["primitives"];
  const Json& out_prims = out["primitives"];

  // Both materials, one primitive each, the texture's bytes unchanged.
  ASSERT_EQ(out_prims.size(), 2u);
  EXPECT_EQ(out_prims[0]["material"], "cloth");
  EXPECT_EQ(out_prims[0]["texture"], layout_["png"]);
  EXPECT_EQ(out_prims[1]["material"], "trim");
  EXPECT_EQ(out_prims[1]["baseColor"], in_prims[1]["baseColor"]);
  // The primitives share the render vertices, in the input's order: the first primitive's,
  // then the second's; each draws its own.
  const size_t per_part = in_prims[0]["uv"].size() / 2;
  for (size_t g = 0; g < 2; ++g)
    for (const Json& id : out_prims[g]["indices"]) {
      EXPECT_GE(id.get<size_t>(), g * per_part);
      EXPECT_LT(id.get<size_t>(), (g + 1) * per_part);
    }

  // UVs within 14 bits of the range [0, 1].
  const std::vector<double> uv_in = joined(in_prims, "uv"), uv_out = out_prims[0]["uv"];
  ASSERT_EQ(uv_in.size(), uv_out.size());
  for (size_t i = 0; i < uv_in.size(); ++i) EXPECT_NEAR(uv_out[i], uv_in[i], 1.0 / (2 * 16383) + 1e-6) << i;

  // Every frame within the tolerance; each seam pair and each vertex of the row both
  // primitives hold at distance 0, with one normal.
  const size_t frames = out["times"].size();
  const double limit = 1e-3 * diagonal(joined(in_prims, "positions", 0)) + 1e-6;
  const uint32_t columns = layout_["columns"], around = layout_["around"], split = layout_["split"];
  std::vector<std::pair<size_t, size_t>> copies;
  for (size_t part = 0; part < 2; ++part)
    for (uint32_t j = 0; j <= split; ++j) copies.push_back({part * per_part + j * columns, part * per_part + j * columns + around});
  for (uint32_t i = 0; i < columns; ++i) copies.push_back({split * columns + i, per_part + i});
  for (size_t f = 0; f < frames; ++f) {
    const std::vector<double> p_in = joined(in_prims, "positions", f), p_out = out_prims[0]["positions"][f],
                              n_out = out_prims[0]["normals"][f];
    ASSERT_EQ(p_in.size(), p_out.size());
    for (size_t i = 0; i < p_in.size(); i += 3)
      EXPECT_LE(std::hypot(p_out[i] - p_in[i], p_out[i + 1] - p_in[i + 1], p_out[i + 2] - p_in[i + 2]), limit);
    for (const auto& [a, b] : copies)
      for (int k = 0; k < 3; ++k) {
        EXPECT_EQ(p_out[3 * a + k], p_out[3 * b + k]) << "frame " << f << " vertices " << a << ", " << b;
        EXPECT_EQ(n_out[3 * a + k], n_out[3 * b + k]) << "frame " << f << " vertices " << a << ", " << b;
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
  EXPECT_EQ(points, 144u);  // one position per vertex: 170 render vertices, 26 of them copies
  unsigned char m[12];
  ASSERT_TRUE(mdd.read(reinterpret_cast<char*>(m), 12));
  const uint32_t bits = uint32_t(m[8]) << 24 | uint32_t(m[9]) << 16 | uint32_t(m[10]) << 8 | m[11];
  float first;
  std::memcpy(&first, &bits, 4);
  EXPECT_NEAR(first, 1.0f / 24, 1e-6f);
}

}  // namespace
}  // namespace dcurve::test
