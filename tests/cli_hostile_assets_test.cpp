// Hostile assets, round two, through the dcurve program (issue 59, input side): an OBJ frame
// folder whose mtllib is a FIFO or a device, a texture larger than --max-memory allows once
// the encoder's copies are counted. Every command
// runs under `timeout`, so a hang fails the test instead of stalling it.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "cli_util.h"
#include "gltf_fixture.h"
#include "test_util.h"

namespace dcurve::test {
namespace cli_hostile_assets {  // named: the sanitized build batches test files together
using nlohmann::json;
namespace fs = std::filesystem;

CommandResult run_limited(const std::string& args) { return run_cli_command("timeout 60 " + cli_program() + " " + args); }

// Three frames of a textured quad in two materials, its library `library`.
void write_obj_folder(const std::string& dir, const std::string& library) {
  fs::create_directories(dir);
  for (int f = 0; f < 3; ++f) {
    std::ofstream out(dir + "/frame_0000" + std::to_string(f) + ".obj");
    out << "mtllib " << library << "\nv 0 0 0\nv 1 0 " << 0.1 * f << "\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        << "usemtl cloth front\nf 1/1 2/2 3/3\nusemtl cloth back\nf 1/1 3/3 4/4 # the other half\n";
  }
}

TEST(CliHostileAssets, ObjMaterialLibrariesAreNeverOpened) {
  TempDir dir;
  ASSERT_EQ(mkfifo((dir / "fifo.mtl").c_str(), 0600), 0);
  for (const std::string& library : {dir / "fifo.mtl", std::string("/dev/zero"), std::string("../../../../etc/shadow")}) {
    fs::remove_all(dir / "in");
    write_obj_folder(dir / "in", library);
    const CommandResult r = run_limited("encode " + (dir / "in") + " -o " + (dir / "o.dcrv") + " --force -q");
    EXPECT_EQ(r.exit_code, 0) << library << ": " << r.output;
    // The library comes back as the name the input gave, in the decoded OBJ.
    ASSERT_EQ(run_limited("decode " + (dir / "o.dcrv") + " -o " + (dir / "out/") + " --force -q").exit_code, 0);
    std::ifstream in(dir / "out/frame_00000.obj");
    std::string first;
    std::getline(in, first);
    EXPECT_EQ(first, "mtllib " + library);
  }
}

// The triangle of gltf_fixture.h with UVs and a material whose base colour is tex.png, a
// file of `bytes` random bytes after a PNG signature (random: zstd cannot make it smaller).
void write_textured_triangle(const TempDir& dir, size_t bytes) {
  write_triangle_buffer(dir / "buf.bin");
  {
    std::ofstream b(dir / "buf.bin", std::ios::binary | std::ios::app);
    const float uv[6] = {0, 0, 1, 0, 0, 1};
    b.write(reinterpret_cast<const char*>(uv), sizeof uv);
  }
  std::string png = "\x89PNG\r\n\x1a\n";
  std::mt19937_64 random(7);
  while (png.size() < bytes) png.push_back(char(random()));
  std::ofstream(dir / "tex.png", std::ios::binary) << png;
  json j = triangle_gltf();
  j["buffers"][0]["byteLength"] = 124;
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 100}, {"byteLength", 24}});
  j["accessors"].push_back({{"bufferView", 5}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}});
  j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = 5;
  j["meshes"][0]["primitives"][0]["material"] = 0;
  j["materials"] = json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  j["textures"] = json::array({{{"source", 0}}});
  j["images"] = json::array({{{"uri", "tex.png"}, {"mimeType", "image/png"}}});
  std::ofstream(dir / "t.gltf") << j.dump();
}

// The largest resident size of any command this test program has run, in bytes.
uint64_t children_peak_bytes() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return uint64_t(u.ru_maxrss) * 1024;
}

TEST(CliHostileAssets, TexturesAreChargedForEveryCopyTheEncodeHolds) {
  // What a texture adds to the encode's peak: the difference between two sizes (the encode's
  // own memory and zstd's workspace are the same for both), per byte of the difference.
  constexpr uint64_t kSmall = 4 << 20, kLarge = 16 << 20, kCopies = 4;
  uint64_t small_peak = 0;
  for (uint64_t bytes : {kSmall, kLarge}) {
    TempDir dir;
    write_textured_triangle(dir, bytes);
    const CommandResult ok = run_limited("encode " + (dir / "t.gltf") + " -o " + (dir / "o.dcrv") + " -q --max-memory " +
                                         std::to_string(kCopies * bytes + (1 << 20)));
    ASSERT_EQ(ok.exit_code, 0) << ok.output;
    if (bytes == kSmall) {
      small_peak = children_peak_bytes();
      continue;
    }
    EXPECT_LE(double(children_peak_bytes() - small_peak) / double(kLarge - kSmall), kCopies * 1.05);
    // Refused, naming the file and the limit, where fewer copies than the encode holds fit.
    const CommandResult refused = run_limited("encode " + (dir / "t.gltf") + " -o " + (dir / "r.dcrv") +
                                              " --max-memory " + std::to_string((kCopies - 1) * bytes));
    EXPECT_EQ(refused.exit_code, 1) << refused.output;
    EXPECT_TRUE(contains(refused.output, dir / "t.gltf") && contains(refused.output, "--max-memory")) << refused.output;
    EXPECT_FALSE(fs::exists(dir / "r.dcrv"));
  }
}

}  // namespace cli_hostile_assets
}  // namespace dcurve::test
