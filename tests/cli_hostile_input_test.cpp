// Hostile input through the dcurve program (issue 47, input side): what used to hang, crash,
// abort or blame the encoder now ends in a clear error naming the input, exit 1. Every
// command runs under `timeout`, so a hang fails the test instead of stalling it.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli_util.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace dcurve::test {
namespace {
using nlohmann::json;
namespace fs = std::filesystem;

// dcurve with `args`, killed after 60 s (exit 124), optionally under a `ulimit -v` (KiB).
CommandResult run_limited(const std::string& args, long virtual_kib = 0) {
  const std::string limit = virtual_kib > 0 ? "ulimit -v " + std::to_string(virtual_kib) + "; " : "";
  return run_cli_command(limit + "timeout 60 " + cli_program() + " " + args);
}

// An error, not a crash, hang or abort: exit 1, the input named, no bare library message.
void expect_clear_error(const CommandResult& r, const std::string& input, const std::string& expected) {
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, input)) << r.output;
  EXPECT_TRUE(contains(r.output, expected)) << r.output;
  EXPECT_FALSE(contains(r.output, "terminate") || contains(r.output, "dcurve: std::")) << r.output;
}

TEST(CliHostileInput, GltfOutsideItsFolderIsNotRead) {
  TempDir dir;
  fs::create_directories(dir / "asset");
  write_triangle_buffer(dir / "secret.bin");
  json j = triangle_gltf();
  j["buffers"][0]["uri"] = "../secret.bin";
  std::ofstream(dir / "asset/t.gltf") << j.dump();
  const std::string encode = "encode " + (dir / "asset/t.gltf") + " -o " + (dir / "o.dcrv");
  expect_clear_error(run_limited(encode), dir / "asset/t.gltf", "outside the glTF's folder");
  EXPECT_FALSE(fs::exists(dir / "o.dcrv"));
  const CommandResult widened = run_limited(encode + " --allow-resources-outside " + (dir.path.string()));
  EXPECT_EQ(widened.exit_code, 0) << widened.output;
}

TEST(CliHostileInput, SpecialFilesNeitherHangNorExhaustMemory) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  ASSERT_EQ(mkfifo((dir / "image.png").c_str(), 0600), 0);
  json j = triangle_gltf();
  j["images"] = json::array({{{"uri", "image.png"}}, {{"uri", "."}}});
  std::ofstream(dir / "t.gltf") << j.dump();
  const CommandResult images = run_limited("encode " + (dir / "t.gltf") + " -o " + (dir / "images.dcrv"));
  EXPECT_EQ(images.exit_code, 0) << images.output;  // images are never opened

  fs::create_symlink("/dev/zero", dir / "zero.pc2");
  ASSERT_EQ(mkfifo((dir / "fifo.pc2").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir / "fifo.obj").c_str(), 0600), 0);
  std::ofstream(dir / "rest.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  expect_clear_error(run_limited("encode " + (dir / "zero.pc2") + " --mesh " + (dir / "rest.obj") + " -o " + (dir / "o.dcrv"), 2000000),
                     dir / "zero.pc2", "is a device");
  expect_clear_error(run_limited("encode " + (dir / "fifo.pc2") + " --mesh " + (dir / "rest.obj") + " -o " + (dir / "o.dcrv")),
                     dir / "fifo.pc2", "is a FIFO");
  const std::string pc2 = dir / "c.pc2";
  {
    std::string b(32, '\0');
    b.replace(0, 11, "POINTCACHE2");
    b[16] = 3;
    b[28] = 2;
    b += std::string(72, '\0');
    std::ofstream(pc2, std::ios::binary) << b;
  }
  expect_clear_error(run_limited("encode " + pc2 + " --mesh " + (dir / "fifo.obj") + " -o " + (dir / "o.dcrv")),
                     dir / "fifo.obj", "is a FIFO");
}

TEST(CliHostileInput, DeepJsonAndHugeDeclarationsAreErrors) {
  TempDir dir;
  write_triangle_buffer(dir / "buf.bin");
  std::string text = triangle_gltf().dump();
  text.insert(text.size() - 1, ",\"extras\":" + std::string(30000, '[') + std::string(30000, ']'));
  std::ofstream(dir / "deep.gltf") << text;
  expect_clear_error(run_limited("encode " + (dir / "deep.gltf") + " -o " + (dir / "o.dcrv")), dir / "deep.gltf",
                     "nested deeper than");

  // 1 KB declaring 67 million vertices in each of 4 arrays (zeros: no bufferView).
  json j = triangle_gltf();
  for (int a : {0, 1}) {
    j["accessors"][a].erase("bufferView");
    j["accessors"][a]["count"] = 1 << 26;
  }
  j["meshes"][0]["primitives"][0].erase("indices");
  j["meshes"][0]["primitives"][0]["targets"] = json::array({{{"POSITION", 1}}, {{"POSITION", 1}}, {{"POSITION", 1}}});
  j["accessors"][4].erase("bufferView");
  j["accessors"][4]["count"] = 6;
  std::ofstream(dir / "huge.gltf") << j.dump();
  expect_clear_error(run_limited("encode " + (dir / "huge.gltf") + " -o " + (dir / "o.dcrv") + " --max-memory 1GiB"),
                     dir / "huge.gltf", "--max-memory");
}

TEST(CliHostileInput, AllocationFailuresNameTheInput) {
  TempDir dir;
  // Readable under the limit, but more than the address space the process is given.
  write_triangle_buffer(dir / "buf.bin");
  json j = triangle_gltf();
  for (int a : {0, 1}) {
    j["accessors"][a].erase("bufferView");
    j["accessors"][a]["count"] = 39999999;
  }
  j["meshes"][0]["primitives"][0].erase("indices");
  std::ofstream(dir / "big.gltf") << j.dump();
  const CommandResult r = run_limited("encode " + (dir / "big.gltf") + " -o " + (dir / "o.dcrv") + " --threads 2", 1500000);
  expect_clear_error(r, dir / "big.gltf", "out of memory");
}

TEST(CliHostileInput, OutOfRangeCoordinatesAreInputErrors) {
  TempDir dir, out;
  std::ofstream(dir / "f0.obj") << "v 0 0 0\nv 1e37 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "f1.obj") << "v 0 0 1\nv 1e37 0 1\nv 0 1 1\nf 1 2 3\n";
  const CommandResult r = run_limited("encode " + dir.path.string() + " -o " + (out / "o.dcrv"));
  expect_clear_error(r, dir / "f0.obj", "a coordinate is not finite and within");
  EXPECT_FALSE(contains(r.output, "internal error"));
}

}  // namespace
}  // namespace dcurve::test
