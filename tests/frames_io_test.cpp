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
  EXPECT_NE(err.find("non-finite"), std::string::npos) << err;
}

}  // namespace
}  // namespace dcurve::test
