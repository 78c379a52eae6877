// Reading frame folders (encoder/io): bad input is refused with the file (and line) named,
// in-process, so the readers' error paths also run under the sanitizers (cli_test checks
// the exit codes the CLI maps them to).
#include <gtest/gtest.h>

#include <fstream>
#include <limits>

#include "encoder/io/frames.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

TEST(FramesIo, ReadsEveryFormatInNameOrder) {
  for (const std::string ext : {"obj", "off", "ply"}) {
    TempDir dir;
    std::ofstream(dir / ("b." + ext)) << square(ext, "1 0.5 0");
    std::ofstream(dir / ("a." + ext)) << square(ext, "1 0 0");
    std::ofstream(dir / "notes.txt") << "not a frame";
    Animation anim;
    std::string err;
    ASSERT_TRUE(read_frame_folder(dir.path.string(), &anim, &err)) << ext << ": " << err;
    EXPECT_EQ(anim.vertex_count, 4u) << ext;
    ASSERT_EQ(anim.frames.size(), 2u) << ext;
    EXPECT_EQ(anim.frames[0][4], 0.0f) << ext;  // a.EXT first: vertex 1's y
    EXPECT_EQ(anim.frames[1][4], 0.5f) << ext;
    EXPECT_EQ(anim.faces, (std::vector<uint32_t>{0, 1, 2, 1, 3, 2})) << ext;
  }
}

TEST(FramesIo, NonFiniteOrUnparsableCoordinatesNameTheLine) {
  for (const std::string ext : {"obj", "off", "ply"}) {
    for (const char* bad : {"nan 0 0", "1 inf 0", "1 0 1e999", "1e39 0 0", "1 x 0"}) {
      TempDir dir;
      std::ofstream(dir / ("a." + ext)) << square(ext, "1 0 0");
      std::ofstream(dir / ("b." + ext)) << square(ext, bad);
      Animation anim;
      std::string err;
      EXPECT_FALSE(read_frame_folder(dir.path.string(), &anim, &err)) << ext << " " << bad;
      const std::string where = "b." + ext + ": line " + std::to_string(square_second_vertex_line(ext));
      EXPECT_NE(err.find(where), std::string::npos) << ext << " " << bad << ": " << err;
    }
  }
}

TEST(FramesIo, InconsistentOrMissingFramesAreRefused) {
  TempDir dir;
  std::string err;
  Animation anim;
  EXPECT_FALSE(read_frame_folder(dir / "absent", &anim, &err));
  EXPECT_NE(err.find("absent"), std::string::npos) << err;
  EXPECT_FALSE(read_frame_folder(dir.path.string(), &anim, &err));  // no frames
  EXPECT_NE(err.find("no .obj"), std::string::npos) << err;

  std::ofstream(dir / "a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "b.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  EXPECT_FALSE(read_frame_folder(dir.path.string(), &anim, &err));
  EXPECT_NE(err.find("b.obj"), std::string::npos) << err;
  EXPECT_NE(err.find("vertices"), std::string::npos) << err;

  std::ofstream(dir / "b.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 3 2\n";  // same count, other face
  EXPECT_FALSE(read_frame_folder(dir.path.string(), &anim, &err));
  EXPECT_NE(err.find("connectivity differs"), std::string::npos) << err;

  std::ofstream(dir / "b.obj") << "v 0 0 0\nv 1 0\nf 1 2 3\n";  // truncated
  EXPECT_FALSE(read_frame_folder(dir.path.string(), &anim, &err));
  EXPECT_NE(err.find("b.obj"), std::string::npos) << err;
}

// Reads one file written with `text` as NAME; false with the error when refused.
bool read_text_mesh(const TempDir& dir, const std::string& name, const std::string& text, std::vector<float>* xyz,
                    std::vector<uint32_t>* faces, std::string* err) {
  std::ofstream(dir / name, std::ios::binary) << text;
  return read_mesh(dir / name, xyz, faces, err);
}

// What OpenMesh's readers would change without a word is refused, naming the file.
TEST(FramesIo, RecordsTheReadersWouldSkipAreRefused) {
  const std::string square4 = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
  const struct {
    const char* name;
    std::string text;
    const char* message;
  } cases[] = {
      {"hex.obj", "v 0 0 0\nv 0x1p-1 0 0\nv 0 1 0\nf 1 2 3\n", "line 2"},
      {"hex.off", "OFF\n3 1 0\n0 0 0\n-0X1P0 0 0\n0 1 0\n3 0 1 2\n", "line 4"},
      {"coff.off", "COFF\n3 1 0\n0 0 0 1 1 1 1\n1 nan 0 1 1 1 1\n0 1 0 1 1 1 1\n3 0 1 2\n", "line 4"},
      {"range.obj", square4 + "f 1 2 3\nf 2 4 5\n", "line 6: vertex index 5 out of range"},
      {"zero.obj", square4 + "f 1 2 3\nf 0 2 3\n", "line 6: vertex index 0 out of range"},
      {"back.obj", square4 + "f -1 -2 -5\n", "line 5: vertex index -5 out of range"},
      {"degenerate.obj", square4 + "vt 0 0\nf 1 2 3\nf 2/1 4/1 2/1\n", "line 7: the face uses vertex 2 twice"},
      {"line.obj", square4 + "f 1 2\n", "line 5: a face needs 3 or more vertices"},
      {"range.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 4\n", "line 8: face 1"},
      {"degenerate.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 1 3\n", "face"},
      {"range.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 7\n", "line 15: face 1"},
      {"short.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n", "ends after 1 of its 2 faces"},
      // Found by the reader fuzz target: OpenMesh's PLY reader crashes on a property before any
      // element; a bare "v" line is a vertex OpenMesh does not read.
      {"header.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 1\nend_header\n0\n", "line 3: malformed PLY header"},
      {"noz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", "no z"},
      {"twice.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nelement vertex 2\nproperty float x\n"
                    "end_header\n0\n0\n0\n", "line 5: malformed PLY header"},  // found by the reader fuzz target
      {"bare.obj", square4 + "v\nf 1 2 3\n", "line 5"},
      {"feed.obj", square4 + "v\f\f\nf 1 2 3\n", "line 5"},
      // OpenMesh's OFF reader reads counts across lines and allocates a face's vertex count.
      {"counts.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 1: an OFF file needs its keyword alone"},
      {"junk.off", "OFF 0.0\n1 0 0\n0 1 0\n", "line 1: an OFF file needs"},
      {"split.off", "OFF\n3\n1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "line 2: an OFF file needs"},
      {"nul.off", std::string("OFF\n3 1 0\n0 0 0\0\n1 0 0\n0 1 0\n3 0 1 2\n", 37), "line 3: a control character"},
      {"huge.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n555555555555 0 1 2\n", "line 6: face 0"},
      {"binary.off", "OFF BINARY\n", "binary OFF is not supported"},
      {"huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                   "property float y\nproperty float z\nend_header\n", "shorter than its PLY header declares"},
      {"huge_ascii.ply", "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n0 0 0\n", "ends after 1 of its 2000000000 vertices"},
  };
  for (const auto& c : cases) {
    TempDir dir;
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string err;
    EXPECT_FALSE(read_text_mesh(dir, c.name, c.text, &xyz, &faces, &err)) << c.name;
    EXPECT_NE(err.find(c.name), std::string::npos) << c.name << ": " << err;
    EXPECT_NE(err.find(c.message), std::string::npos) << c.name << ": " << err;
  }
}

// Vertex i read is vertex i of the file, whatever the faces: three triangles on one edge
// (which OpenMesh's mesh kernel cannot hold) keep their ids, a pentagon becomes a fan.
TEST(FramesIo, NonManifoldFacesAndPolygonsKeepEveryVertexAndFace) {
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 0.5 1 0\nv 0.5 -1 0\nv 0.5 0 1\nv 2 0 0\nv 3 0 0\nv 3.5 1 0\nv 2.5 2 0\n"
      "v 1.5 1 0\nf 1 2 3\nf 2 1 4\nf 1 2 5\nf 6 7 8 9 10\n";
  TempDir dir;
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string err;
  ASSERT_TRUE(read_text_mesh(dir, "fin.obj", text, &xyz, &faces, &err)) << err;
  ASSERT_EQ(xyz.size(), 30u);
  EXPECT_EQ(xyz[3 * 9], 1.5f);  // vertex 9 is the file's tenth vertex
  EXPECT_EQ(faces, (std::vector<uint32_t>{0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 6, 7, 5, 7, 8, 5, 8, 9}));
}

// What write_mesh writes reads back to exactly the same floats and faces, in every format,
// at any magnitude the readers take (text coordinates are the shortest that round-trip).
TEST(FramesIo, WrittenMeshesReadBackExactly) {
  const std::vector<float> xyz = {1.3e-30f, -2.5e-7f, 3.1415927f, 123456.79f, 1.5e-38f, -0.1f,
                                  7.0f,     1e18f,    -9.9e17f,   0.33333334f, 2.0f,  -1.2e-38f};
  const std::vector<uint32_t> faces = {0, 1, 2, 1, 0, 3, 0, 1, 2};  // a repeated triangle, kept
  for (const std::string ext : {"obj", "off", "ply"}) {
    TempDir dir;
    std::string err;
    ASSERT_TRUE(write_mesh(dir / ("m." + ext), xyz.data(), 4, faces, &err)) << err;
    std::vector<float> back;
    std::vector<uint32_t> back_faces;
    ASSERT_TRUE(read_mesh(dir / ("m." + ext), &back, &back_faces, &err)) << ext << ": " << err;
    EXPECT_EQ(back, xyz) << ext;
    EXPECT_EQ(back_faces, faces) << ext;
  }
}

TEST(FramesIo, ValidateAnimationChecksCountsIndicesAndValues) {
  Animation anim;
  anim.vertex_count = 3;
  anim.faces = {0, 1, 2};
  anim.frames = {{0, 0, 0, 1, 0, 0, 0, 1, 0}};
  std::string err;
  EXPECT_TRUE(validate_animation(anim, &err)) << err;
  Animation bad = anim;
  bad.frames.clear();
  EXPECT_FALSE(validate_animation(bad, &err));
  bad = anim;
  bad.faces = {0, 1, 3};
  EXPECT_FALSE(validate_animation(bad, &err));
  EXPECT_NE(err.find("out of range"), std::string::npos) << err;
  bad = anim;
  bad.frames.push_back({0, 0, 0});
  EXPECT_FALSE(validate_animation(bad, &err));
  EXPECT_NE(err.find("frame 1"), std::string::npos) << err;
  bad = anim;
  bad.frames[0][4] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(validate_animation(bad, &err));
  EXPECT_NE(err.find("not finite"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve::test
