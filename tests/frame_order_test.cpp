// Frame folders in frame-number order: unpadded numbers sort as numbers, and a gap, a
// repeated number or a stray unnumbered file is an error naming the files.
#include <gtest/gtest.h>

#include "encoder/io/frame_order.h"
#include "encoder/io/frames.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

TEST(FrameOrder, UnpaddedNumbersReadInNumberOrder) {
  TempDir dir;
  for (int i = 1; i <= 12; ++i) write_triangle_obj(dir / ("anim." + std::to_string(i) + ".obj"), i);
  Animation anim;
  std::string err;
  ASSERT_TRUE(read_frame_folder(dir.path.string(), &anim, &err)) << err;
  ASSERT_EQ(anim.frames.size(), 12u);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(anim.frames[i][2], float(i + 1)) << "frame " << i;
}

TEST(FrameOrder, GapNamesTheFilesAroundIt) {
  std::vector<std::filesystem::path> files = {"d/anim.1.obj", "d/anim.2.obj", "d/anim.10.obj", "d/anim.3.obj"};
  std::string err;
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("frames 4-9 missing between anim.3.obj and anim.10.obj"), std::string::npos) << err;
  files = {"d/f_1.obj", "d/f_3.obj"};
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("frame 2 missing between f_1.obj and f_3.obj"), std::string::npos) << err;
}

TEST(FrameOrder, DuplicateNumberNamesBothFiles) {
  std::vector<std::filesystem::path> files = {"d/anim.5.obj", "d/anim.05.obj", "d/anim.4.obj"};
  std::string err;
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("anim.05.obj and anim.5.obj are both frame 5"), std::string::npos) << err;
  files = {"d/a_1.obj", "d/a_1.ply"};
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("are both frame 1"), std::string::npos) << err;
}

TEST(FrameOrder, UnnumberedNamesSortByNameUnlessMixed) {
  std::vector<std::filesystem::path> files = {"d/b.obj", "d/a.obj", "d/c.obj"};
  std::string err;
  ASSERT_TRUE(order_frame_files(&files, &err)) << err;
  EXPECT_EQ(files, (std::vector<std::filesystem::path>{"d/a.obj", "d/b.obj", "d/c.obj"}));
  files = {"d/rest.obj", "d/f1.obj", "d/f2.obj"};
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("d/rest.obj has no frame number but f1.obj has"), std::string::npos) << err;
}

TEST(FrameOrder, FrameNumbersMayStartAnywhere) {
  std::vector<std::filesystem::path> files = {"d/x1001.obj", "d/x999.obj", "d/x1000.obj"};
  std::string err;
  ASSERT_TRUE(order_frame_files(&files, &err)) << err;
  EXPECT_EQ(files, (std::vector<std::filesystem::path>{"d/x999.obj", "d/x1000.obj", "d/x1001.obj"}));
}

}  // namespace
}  // namespace dcurve::test
