// The write path under every output (encoder/io/output_file, output_folder): temporary names
// that fit the name limit, no replacing without `replace`, a second writer of a new name or
// a folder refused, and the glTF writer's size known before it writes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "encoder/io/gltf_writer.h"
#include "encoder/io/output_file.h"
#include "encoder/io/output_folder.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

namespace fs = std::filesystem;

TEST(OutputFile, TemporaryNamesFitTheLimitAndKeepCharactersWhole) {
  const std::string random = "0123456789";
  for (size_t length : {1, 200, 240, 241, 250, 255}) {
    const std::string name = std::string(length, 'a');
    const std::string tmp = temporary_name("/some/dir/" + name, random, 255);
    EXPECT_LE(fs::path(tmp).filename().string().size(), 255u) << length;
    EXPECT_EQ(fs::path(tmp).parent_path(), "/some/dir");
    EXPECT_NE(tmp, "/some/dir/" + name);
  }
  // "é" is two bytes: a cut never leaves half of one.
  std::string name;
  for (int i = 0; i < 127; ++i) name += "\xc3\xa9";
  const std::string tmp = fs::path(temporary_name(name, random, 255)).filename().string();
  const std::string kept = tmp.substr(0, tmp.find(".tmp."));
  EXPECT_EQ(kept.size() % 2, 0u);
  EXPECT_LE(tmp.size(), 255u);
}

TEST(OutputFile, ARegularFileIsReplacedOnlyWhenAsked) {
  TempDir dir;
  std::ofstream(dir / "a.bin") << "old";
  std::string err;
  OutputFile out;
  EXPECT_FALSE(out.open(dir / "a.bin", false, &err));
  EXPECT_NE(err.find("--force"), std::string::npos) << err;
  ASSERT_TRUE(out.open(dir / "a.bin", true, &err)) << err;
  ASSERT_TRUE(out.write("new", 3, &err) && out.commit(&err)) << err;
  EXPECT_EQ(file_text(dir / "a.bin"), "new");
}

// Two writers of a new name: the one that finishes second fails and the first's file stays.
TEST(OutputFile, TheSecondWriterOfANewNameFails) {
  TempDir dir;
  std::string err;
  OutputFile a, b;
  ASSERT_TRUE(a.open(dir / "n.bin", false, &err)) << err;
  ASSERT_TRUE(b.open(dir / "n.bin", false, &err)) << err;
  ASSERT_TRUE(a.write("a", 1, &err) && a.commit(&err)) << err;
  ASSERT_TRUE(b.write("b", 1, &err));
  EXPECT_FALSE(b.commit(&err));
  EXPECT_NE(err.find("appeared"), std::string::npos) << err;
  EXPECT_EQ(file_text(dir / "n.bin"), "a");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

void stage(OutputFolder& folder, const std::string& name, const std::string& text) {
  std::string err;
  ASSERT_TRUE(folder.write_file(name, text.data(), text.size(), &err)) << err;
}

TEST(OutputFolder, TwoWritersOfAFolderNeverMix) {
  TempDir dir;
  std::string err;
  {  // a new folder: the second to finish fails
    OutputFolder a, b;
    ASSERT_TRUE(a.open(dir / "new", false, &err)) << err;
    ASSERT_TRUE(b.open(dir / "new/", false, &err)) << err;
    stage(a, "frame_00000.obj", "a");
    stage(b, "frame_00000.obj", "b");
    stage(b, "frame_00001.obj", "b");
    ASSERT_TRUE(a.commit(&err)) << err;
    EXPECT_FALSE(b.commit(&err));
  }
  EXPECT_EQ(file_text(dir / "new/frame_00000.obj"), "a");
  EXPECT_FALSE(fs::exists(dir / "new/frame_00001.obj"));
  {  // an existing folder: the second cannot even start
    OutputFolder a, b;
    ASSERT_TRUE(a.open(dir / "new", true, &err)) << err;
    EXPECT_FALSE(b.open(dir / "new", true, &err));
    EXPECT_NE(err.find("another process"), std::string::npos) << err;
    stage(a, "frame_00000.ply", "c");
    ASSERT_TRUE(a.commit(&err)) << err;
  }
  EXPECT_EQ(file_text(dir / "new/frame_00000.ply"), "c");
  EXPECT_FALSE(fs::exists(dir / "new/frame_00000.obj"));
  // Nothing left beside: no staging folder, no old frames' folder.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
}

TEST(OutputFolder, AnUncommittedFolderLeavesTheOldOneAsItWas) {
  TempDir dir;
  fs::create_directory(dir / "out");
  std::ofstream(dir / "out/frame_00000.obj") << "old";
  fs::permissions(dir / "out", fs::perms(0750));
  std::string err;
  {
    OutputFolder f;
    ASSERT_TRUE(f.open(dir / "out", true, &err)) << err;
    stage(f, "frame_00000.obj", "new");
  }
  EXPECT_EQ(file_text(dir / "out/frame_00000.obj"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path), fs::directory_iterator()), 1);
  OutputFolder f;
  ASSERT_TRUE(f.open(dir / "out", true, &err)) << err;
  stage(f, "frame_00000.obj", "new");
  ASSERT_TRUE(f.commit(&err)) << err;
  EXPECT_EQ(file_text(dir / "out/frame_00000.obj"), "new");
  EXPECT_EQ(fs::status(dir / "out").permissions(), fs::perms(0750));  // the folder's mode is kept
}

// The size the writer promises before writing is what it writes (.glb: exactly; .gltf: at
// most, its bounds may print shorter than the placeholders), base64 included.
TEST(GltfWriterSize, TheCheckedSizeIsTheWrittenSize) {
  TempDir dir;
  const std::vector<uint32_t> faces = grid_faces(3, 3);
  for (uint32_t frames : {1u, 2u, 7u}) {
    for (bool binary : {true, false}) {
      const std::string path = dir / (binary ? "s.glb" : "s.gltf");
      GltfWriter w(9, faces, frames, 24, binary);
      std::string err;
      ASSERT_TRUE(w.open(path, true, &err)) << err;
      for (uint32_t f = 0; f < frames; ++f) {
        std::vector<float> xyz;
        for (int v = 0; v < 9; ++v) xyz.insert(xyz.end(), {float(v % 3) / 3.0f, float(v / 3), 0.001f * f * v});
        ASSERT_TRUE(w.add_frame(xyz.data(), &err)) << err;
      }
      ASSERT_TRUE(w.finish(&err)) << err;
      const uint64_t promised = GltfWriter::file_bytes(9, faces.size(), frames, binary);
      const uint64_t buffer = 4 * faces.size() + 36 * frames + 4 * frames + 4 * frames * (frames - 1);
      if (binary) EXPECT_EQ(fs::file_size(path), promised) << frames;
      else EXPECT_LE(fs::file_size(path), promised) << frames;
      EXPECT_GT(fs::file_size(path), binary ? buffer : buffer * 4 / 3) << frames;
    }
  }
  std::string err;
  EXPECT_TRUE(GltfWriter::check_size(3, 3, 15000, true, &err)) << err;  // ~900 MB binary
  EXPECT_FALSE(GltfWriter::check_size(3, 3, 15000, false, &err));       // ~1.2 GB as base64
}

}  // namespace
}  // namespace dcurve::test
