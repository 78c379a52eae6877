// Frame folders in frame-number order: unpadded numbers sort as numbers, a uniform step
// between the numbers is a frame rate, and a gap, an irregular step, a repeated number or a
// stray unnumbered file is an error naming the files.
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
  files = {"d/f_1.obj", "d/f_2.obj", "d/f_4.obj"};
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("frame 3 missing between f_2.obj and f_4.obj"), std::string::npos) << err;
}

// A DCC writing every second frame: the step is returned, the order is the numbers'.
TEST(FrameOrder, UniformStepIsAccepted) {
  std::vector<std::filesystem::path> files = {"d/frame_00004.obj", "d/frame_00000.obj", "d/frame_00002.obj"};
  std::string err;
  long long step = 0;
  ASSERT_TRUE(order_frame_files(&files, &err, &step)) << err;
  EXPECT_EQ(step, 2);
  EXPECT_EQ(files, (std::vector<std::filesystem::path>{"d/frame_00000.obj", "d/frame_00002.obj", "d/frame_00004.obj"}));
  files = {"d/a.1001.obj", "d/a.1006.obj", "d/a.1011.obj"};
  ASSERT_TRUE(order_frame_files(&files, &err, &step)) << err;
  EXPECT_EQ(step, 5);
}

// A gap unlike the first one is an error that names the two files around it.
TEST(FrameOrder, IrregularStepNamesTheFiles) {
  std::vector<std::filesystem::path> files = {"d/frame_00000.obj", "d/frame_00002.obj", "d/frame_00003.obj"};
  std::string err;
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("frame_00002.obj and frame_00003.obj are 1 frame apart, but frame_00000.obj and "
                     "frame_00002.obj are 2: an irregular frame step"),
            std::string::npos)
      << err;
  files = {"d/frame_00000.obj", "d/frame_00002.obj", "d/frame_00008.obj"};
  EXPECT_FALSE(order_frame_files(&files, &err));
  EXPECT_NE(err.find("frames 4-6 missing between frame_00002.obj and frame_00008.obj (the frames step by 2)"),
            std::string::npos)
      << err;
}

// The frame rate follows from the step: the numbers count at kFolderFrameRate.
TEST(FrameOrder, FolderFrameRateFollowsTheStep) {
  TempDir dir;
  for (int i = 0; i < 3; ++i) write_triangle_obj(dir / ("frame_0000" + std::to_string(2 * i) + ".obj"), i);
  Animation anim;
  std::string err;
  ASSERT_TRUE(read_frame_folder(dir.path.string(), &anim, &err)) << err;
  ASSERT_EQ(anim.frames.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(anim.frames[i][2], float(i)) << "frame " << i;
  EXPECT_DOUBLE_EQ(anim.frame_rate, kFolderFrameRate / 2);
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
