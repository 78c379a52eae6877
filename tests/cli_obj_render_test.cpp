// OBJ frames with texture coordinates, normals and materials (`f v/vt/vn`, `usemtl`,
// `mtllib`): encoded and decoded back to OBJ, every corner keeps its UV within the stated
// precision, the faces keep their materials and the file its material library; vertex i stays
// vertex i, and a glTF decoded from the same file has the render vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cli_util.h"
#include "encoder/io/frames.h"
#include "encoder/io/obj_reader.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

// A 4 x 4 grid of quads whose UV chart is cut along x = 2 (the corners there take u = 0.5 on
// the left faces and u = 0.6 on the right ones), left half "red", right half "blue".
void write_frames(const TempDir& dir, int frames) {
  for (int f = 0; f < frames; ++f) {
    std::string text = "mtllib cloth.mtl\n";
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i)
        text += "v " + std::to_string(i * 0.25) + " " + std::to_string(j * 0.25) + " " +
                std::to_string(0.05 * std::sin(i + j + 0.5 * f)) + "\n";
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 4; ++i) text += "vt " + std::to_string(i * 0.125) + " " + std::to_string(j * 0.25) + "\n";
    for (int j = 0; j <= 4; ++j) text += "vt 0.6 " + std::to_string(j * 0.25) + "\n";  // the right side of the cut
    text += "vn 0 0 1\n";
    for (const char* side : {"red", "blue"}) {
      text += std::string("usemtl ") + side + "\n";
      for (int j = 0; j < 4; ++j)
        for (int i = side[0] == 'r' ? 0 : 2; i < (side[0] == 'r' ? 2 : 4); ++i) {
          auto corner = [&](int a, int b) {
            const int v = b * 5 + a + 1;
            const int vt = a == 2 && side[0] == 'b' ? 26 + b : v;
            return std::to_string(v) + "/" + std::to_string(vt) + "/1";
          };
          text += "f " + corner(i, j) + " " + corner(i + 1, j) + " " + corner(i + 1, j + 1) + " " + corner(i, j + 1) + "\n";
        }
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%05d.obj", f);
    std::FILE* out = std::fopen((dir / ("in/" + std::string(name))).c_str(), "w");
    std::fputs(text.c_str(), out);
    std::fclose(out);
  }
}

TEST(CliObjRender, UvsNormalsAndMaterialsComeBackInObj) {
  TempDir dir;
  std::filesystem::create_directories(dir / "in");
  write_frames(dir, 4);
  CommandResult e = run_cli("encode " + dir / "in -o " + dir / "x.dcrv --tolerance 1e-3 -q");
  ASSERT_EQ(e.exit_code, 0) << e.output;
  ASSERT_EQ(run_cli("decode " + dir / "x.dcrv -o " + dir / "out/").exit_code, 0);
  ObjMesh in_mesh, out_mesh;
  std::string err;
  ASSERT_TRUE(read_obj(dir / "in/frame_00002.obj", &in_mesh, &err)) << err;
  ASSERT_TRUE(read_obj(dir / "out/frame_00002.obj", &out_mesh, &err)) << err;
  const ObjCorners& in = in_mesh.corners;
  const ObjCorners& out = out_mesh.corners;
  EXPECT_EQ(out.material_library, "cloth.mtl");
  EXPECT_EQ(out.materials, in.materials);
  // The same triangles, materials and corner UVs (14 bits over u's range [0, 0.6], v's [0, 1]),
  // in the face coder's order: matched by their vertices.
  ASSERT_EQ(out.vertex.size(), in.vertex.size());
  std::map<std::array<uint32_t, 3>, size_t> in_triangle;
  for (size_t t = 0; t < in.vertex.size() / 3; ++t) in_triangle[{in.vertex[3 * t], in.vertex[3 * t + 1], in.vertex[3 * t + 2]}] = t;
  for (size_t t = 0; t < out.vertex.size() / 3; ++t) {
    // A triangle may start at another corner: rotate it to the input's first vertex.
    size_t rot = 0;
    std::array<uint32_t, 3> key{};
    for (; rot < 3; ++rot) {
      key = {out.vertex[3 * t + rot], out.vertex[3 * t + (rot + 1) % 3], out.vertex[3 * t + (rot + 2) % 3]};
      if (in_triangle.count(key)) break;
    }
    ASSERT_LT(rot, 3u) << "triangle " << t << " is not an input triangle";
    const size_t s = in_triangle[key];
    EXPECT_EQ(out.materials[size_t(out.face_material[t])], in.materials[size_t(in.face_material[s])]);
    for (size_t k = 0; k < 3; ++k) {
      const int64_t a = out.texcoord[3 * t + (rot + k) % 3], b = in.texcoord[3 * s + k];
      ASSERT_GE(a, 0);
      EXPECT_NEAR(out.texcoords[2 * a], in.texcoords[2 * b], 0.6 / (2 * 16383) + 1e-6);
      EXPECT_NEAR(out.texcoords[2 * a + 1], in.texcoords[2 * b + 1], 1.0 / (2 * 16383) + 1e-6);
      EXPECT_GE(out.normal[3 * t + k], 0);
    }
  }
  // Vertex i is vertex i: the positions within the tolerance of the same input vertex.
  std::vector<float> a, b;
  std::vector<uint32_t> fa, fb;
  ASSERT_TRUE(read_mesh(dir / "in/frame_00002.obj", &a, &fa, &err)) << err;
  ASSERT_TRUE(read_mesh(dir / "out/frame_00002.obj", &b, &fb, &err)) << err;
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 1e-3 * std::sqrt(2.0) * 1.01);
}

}  // namespace
}  // namespace dcurve::test
