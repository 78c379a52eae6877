// The CLI against hostile paths and inputs (issue 38): planted links, special files and
// inputs as outputs are refused; inputs the mesh readers would change are refused or carried
// through exactly; decoded OBJ coordinates read back to the decoded floats; option values
// that are not numbers in range (NaN included) are bad usage; `info` describes only files
// that decode and prints what they store safely. DCURVE_TEST_CLI runs them against another
// build (cli_util.h).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "codec/compress/container_writer.h"
#include "codec/decompress/container_reader.h"
#include "encoder/io/files.h"
#include "encoder/io/output_file.h"
#include "cli_util.h"
#include "container_bytes.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

namespace fs = std::filesystem;

// Three frames of a 4 x 4 sheet whose middle rises: `scale` times unit coordinates.
Animation small_sheet(double scale = 1.0) {
  Animation a;
  a.vertex_count = 16;
  a.faces = grid_faces(4, 4);
  for (int f = 0; f < 3; ++f) {
    std::vector<float> xyz;
    for (int v = 0; v < 16; ++v) {
      const double x = v % 4, y = v / 4, z = (v == 5 || v == 6) ? 0.3 * f : 0.05 * f * x;
      for (double c : {x, y, z}) xyz.push_back(float(scale * c));
    }
    a.frames.push_back(xyz);
  }
  return a;
}

// Writes `anim` as DIR/frames and encodes it to DIR/c.dcrv; the encode's result.
CommandResult encode_sheet(const TempDir& dir, const Animation& anim, const std::string& options = "") {
  std::string err;
  EXPECT_TRUE(write_frame_folder(dir / "frames", anim, "obj", &err)) << err;
  return run_cli("encode " + dir / "frames" + " -o " + dir / "c.dcrv --effort 1 " + options);
}

TEST(CliRobustness, DecodeNeverWritesThroughALinkPlantedAtItsTemporaryName) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  fs::create_directory(dir / "out");
  std::ofstream(dir / "victim.txt") << "precious";
  for (const char* planted : {"frame_00000.obj.tmp.obj", "frame_00001.obj.tmp.obj"})
    fs::create_symlink(dir / "victim.txt", dir / (std::string("out/") + planted));
  CommandResult r = run_cli("decode " + dir / "c.dcrv -o " + dir / "out --force");  // the links look like frames
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(file_text(dir / "victim.txt"), "precious");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(dir / "out/frame_00000.obj")));
}

TEST(CliRobustness, AnOutputThatIsALinkOrASpecialFileIsRefused) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  ASSERT_EQ(mkfifo((dir / "fifo.dcrv").c_str(), 0644), 0);
  std::ofstream(dir / "victim.txt") << "precious";
  fs::create_symlink(dir / "victim.txt", dir / "link.dcrv");
  for (const char* out : {"fifo.dcrv", "link.dcrv"}) {
    CommandResult r = run_cli("encode " + dir / "frames" + " -o " + dir / out + " --effort 1");
    EXPECT_EQ(r.exit_code, 1) << out << ": " << r.output;
    EXPECT_NE(r.output.find(dir / out), std::string::npos) << r.output;
  }
  EXPECT_TRUE(fs::is_fifo(dir / "fifo.dcrv"));
  EXPECT_TRUE(fs::is_symlink(dir / "link.dcrv"));
  EXPECT_EQ(file_text(dir / "victim.txt"), "precious");
  // A decoded frame's name taken by a FIFO: refused, the FIFO stays.
  fs::create_directory(dir / "out");
  ASSERT_EQ(mkfifo((dir / "out/frame_00001.obj").c_str(), 0644), 0);
  CommandResult r = run_cli("decode " + dir / "c.dcrv -o " + dir / "out");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("frame_00001.obj"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_fifo(dir / "out/frame_00001.obj"));
}

TEST(CliRobustness, AnOutputThatIsAnInputFrameIsRefused) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  const std::string frame = dir / "frames/frame_00001.obj";
  const std::string before = file_text(frame);
  CommandResult r = run_cli("encode " + dir / "frames" + " -o " + frame + " --effort 1");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("input"), std::string::npos) << r.output;
  EXPECT_EQ(file_text(frame), before);
}

// Input that OpenMesh's readers would silently change: each refused with the file named.
TEST(CliRobustness, InputTheReadersWouldChangeIsRefused) {
  const std::string square = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
  const struct {
    const char* name;
    std::string text;
    const char* message;
  } cases[] = {
      {"a.obj", "v 0 0 0\nv 0x1p0 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n", "a.obj: line 2"},  // hex float
      {"a.obj", square + "f 1 2 3\nf 2 4 9\n", "a.obj: line 6: vertex index 9 out of range"},
      {"a.obj", square + "f 1 2 3\nf 2 4 4\n", "a.obj: line 6: the face uses vertex 4 twice"},
      {"a.off", "COFF\n4 2 0\n0 0 0 1 1 1 1\nnan 0 0 1 1 1 1\n0 1 0 1 1 1 1\n1 1 0 1 1 1 1\n3 0 1 2\n3 1 3 2\n",
       "a.off: line 4"},  // COFF with a NaN
  };
  for (const auto& c : cases) {  // every frame alike: the readers would change each the same way
    TempDir dir;
    fs::create_directory(dir / "frames");
    for (const char* frame : {"a", "b"})
      std::ofstream(dir / (std::string("frames/") + frame + fs::path(c.name).extension().string())) << c.text;
    CommandResult r = run_cli("encode " + dir / "frames" + " -o " + dir / "c.dcrv --effort 1");
    EXPECT_EQ(r.exit_code, 1) << c.text << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.text << r.output;
    EXPECT_FALSE(fs::exists(dir / "c.dcrv")) << c.text;
  }
}

// Decodes DIR/c.dcrv into DIR/out (replacing its frames) and reads frame 0 back.
void decode_first_frame(const TempDir& dir, std::vector<float>* xyz, std::vector<uint32_t>* faces) {
  CommandResult r = run_cli("decode " + dir / "c.dcrv -o " + dir / "out --force");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::string err;
  ASSERT_TRUE(read_mesh(dir / "out/frame_00000.obj", xyz, faces, &err)) << err;
}

// A non-manifold edge (three triangles on one edge) and a pentagon: every vertex keeps its
// id and place, every face is kept (the pentagon as a fan of three triangles).
TEST(CliRobustness, NonManifoldEdgesAndPolygonsAreCarriedThroughExactly) {
  TempDir dir;
  fs::create_directory(dir / "frames");
  const std::string faces = "f 1 2 3\nf 2 1 4\nf 1 2 5\nf 6 7 8 9 10\n";
  for (int f = 0; f < 2; ++f) {
    std::ofstream out(dir / ("frames/frame_0000" + std::to_string(f) + ".obj"));
    out << "v 0 0 0\nv 1 0 0\nv 0.5 1 " << 0.1 * f << "\nv 0.5 -1 0\nv 0.5 0 1\n"
        << "v 2 0 0\nv 3 0 0\nv 3.5 1 0\nv 2.5 2 0\nv 1.5 1 0\n" << faces;
  }
  CommandResult r = run_cli("encode " + dir / "frames" + " -o " + dir / "c.dcrv --effort 1 --keep-face-order");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<float> xyz, in_xyz;
  std::vector<uint32_t> back, in_faces;
  decode_first_frame(dir, &xyz, &back);
  std::string err;
  ASSERT_TRUE(read_mesh(dir / "frames/frame_00000.obj", &in_xyz, &in_faces, &err)) << err;
  ASSERT_EQ(xyz.size(), in_xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i) EXPECT_NEAR(xyz[i], in_xyz[i], 1e-2) << i;
  const std::vector<uint32_t> fans = {0, 1, 2, 1, 0, 3, 0, 1, 4, 5, 6, 7, 5, 7, 8, 5, 8, 9};
  EXPECT_EQ(back, fans);
  // The default, the face coder's traversal order, keeps the same triangles and windings.
  r = run_cli("encode " + dir / "frames" + " -o " + dir / "c.dcrv --effort 1 --force");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  decode_first_frame(dir, &xyz, &back);
  EXPECT_EQ(canonical_triangles(back), canonical_triangles(fans));
}

// Decoded coordinates are written as the shortest text that reads back to the decoded float:
// at any scale the decoded file meets the tolerance.
TEST(CliRobustness, DecodedObjMeetsTheToleranceAtAnyScale) {
  for (double scale : {1e-6, 1e-30, 1e6}) {
    TempDir dir;
    const Animation anim = small_sheet(scale);
    CommandResult r = encode_sheet(dir, anim, "--tolerance 1e-3");
    ASSERT_EQ(r.exit_code, 0) << scale << r.output;
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    decode_first_frame(dir, &xyz, &faces);
    ASSERT_EQ(xyz.size(), anim.frames[0].size());
    const double L = bbox_diagonal(anim.frames[0]);
    double worst = 0;
    for (size_t v = 0; v < xyz.size(); v += 3)
      worst = std::max(worst, std::hypot(xyz[v] - anim.frames[0][v], xyz[v + 1] - anim.frames[0][v + 1],
                                         xyz[v + 2] - anim.frames[0][v + 2]) / L);
    EXPECT_LE(worst, 1e-3) << "scale " << scale;
  }
}

// The documented minimum tolerance works on a mesh about the origin; below it is bad usage.
// Far from the origin float32 coordinates cannot hold it: refused with the reachable
// minimum named (not an internal error), and that minimum works.
TEST(CliRobustness, TheDocumentedToleranceRangeWorks) {
  Animation centred = small_sheet();
  for (auto& frame : centred.frames)
    for (size_t i = 0; i < frame.size(); i += 3) frame[i] -= 1.5f, frame[i + 1] -= 1.5f;
  TempDir dir;
  CommandResult r = encode_sheet(dir, centred, "--tolerance 1e-6 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_LE(nlohmann::json::parse(r.output)["max_error"].get<double>(), 1e-6);
  EXPECT_EQ(run_cli("encode " + dir / "frames -o " + dir / "d.dcrv --tolerance 1e-7").exit_code, 2);

  Animation far = small_sheet();
  for (auto& frame : far.frames)
    for (size_t i = 0; i < frame.size(); i += 3) frame[i] += 1000.0f;
  TempDir dir2;
  r = encode_sheet(dir2, far, "--tolerance 1e-5");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const size_t at = r.output.find("float32 coordinates hold for this input, ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double reachable = std::stod(r.output.substr(at + 41));
  EXPECT_GT(reachable, 1e-5);
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.3g", reachable * 1.01);
  r = run_cli("encode " + dir2 / "frames -o " + dir2 / "c.dcrv --effort 1 --json --tolerance " + tolerance);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_LE(nlohmann::json::parse(r.output)["max_error"].get<double>(), std::stod(tolerance));
}

TEST(CliRobustness, NanOptionValuesAreBadUsage) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  EXPECT_EQ(run_cli("decode " + dir / "c.dcrv -o " + dir / "out --t nan").exit_code, 2);
  EXPECT_FALSE(fs::exists(dir / "out"));
  for (const char* option : {"--tolerance nan", "--grid nan", "--tolerance inf", "--grid -nan"})
    EXPECT_EQ(run_cli("encode " + dir / "frames -o " + dir / "d.dcrv " + option).exit_code, 2) << option;
  EXPECT_EQ(run_cli("bench " + dir / "frames --tolerance nan").exit_code, 2);
}

// The file with META's vertex count one higher (its first field, a u32), checksums fixed.
std::vector<uint8_t> with_vertex_count_off_by_one(const std::vector<uint8_t>& bytes) {
  testing::RawFile f = testing::split_file(bytes);
  EXPECT_EQ(f.sections.at(0).tag, "META");
  EXPECT_EQ(f.sections[0].flags & 2, 0);  // stored plainly
  f.sections[0].stored.at(0) += 1;
  return testing::assemble(f);
}

TEST(CliRobustness, InfoRefusesWhatDecodeRefuses) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(read_file(dir / "c.dcrv", &bytes, &err)) << err;
  bytes = with_vertex_count_off_by_one(bytes);
  ASSERT_TRUE(write_file_atomic(dir / "bad.dcrv", bytes.data(), bytes.size(), &err)) << err;
  EXPECT_EQ(run_cli("decode " + dir / "bad.dcrv -o " + dir / "out").exit_code, 1);
  CommandResult r = run_cli("info " + dir / "bad.dcrv");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(dir / "bad.dcrv"), std::string::npos) << r.output;
}

// Units are bytes from the file: JSON stays valid, text escapes them.
TEST(CliRobustness, InfoPrintsUnitsThatAreNotUtf8OrHoldEscapes) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(read_file(dir / "c.dcrv", &bytes, &err)) << err;
  Model m;
  ASSERT_TRUE(read_container(bytes.data(), bytes.size(), &m, &err)) << err;
  m.meta.units = "\xff\x1b[2Jm";
  bytes = write_container(m);
  ASSERT_TRUE(write_file_atomic(dir / "units.dcrv", bytes.data(), bytes.size(), &err)) << err;
  CommandResult r = run_cli("info --json " + dir / "units.dcrv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NO_THROW(nlohmann::json::parse(r.output)) << r.output;
  r = run_cli("info " + dir / "units.dcrv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find('\x1b'), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\\x1b[2Jm"), std::string::npos) << r.output;
}

// A folder decode killed part-way leaves neither the output folder nor its staging folder.
TEST(CliRobustness, TermSignalDuringAFolderDecodeLeavesNothing) {
  TempDir dir;
  ASSERT_EQ(encode_sheet(dir, small_sheet()).exit_code, 0);
  const std::string cli = cli_program();
  const std::string input = dir / "c.dcrv", output = dir / "out";
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    execl(cli.c_str(), cli.c_str(), "decode", input.c_str(), "-o", output.c_str(), "--frames", "1000000", "--quiet",
          static_cast<char*>(nullptr));
    _exit(127);
  }
  auto staged_frames = [&] {  // frames written into a .dcurve-partial-* folder so far
    size_t n = 0;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir.path, ec))
      if (e.path().filename().string().rfind(".dcurve-partial-", 0) == 0)
        for (auto it = fs::directory_iterator(e.path(), ec); !ec && it != fs::directory_iterator(); ++it) ++n;
    return n;
  };
  const auto start = std::chrono::steady_clock::now();
  while (staged_frames() < 10 && std::chrono::steady_clock::now() - start < std::chrono::seconds(30))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  const size_t seen = staged_frames();
  kill(child, SIGTERM);
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_GE(seen, 10u);
  ASSERT_TRUE(WIFSIGNALED(status)) << "exit " << WEXITSTATUS(status);
  EXPECT_EQ(WTERMSIG(status), SIGTERM);
  EXPECT_EQ(staged_frames(), 0u);
  size_t left = 0;
  for (auto it = fs::directory_iterator(dir.path); it != fs::directory_iterator(); ++it)
    left += it->path().filename().string().rfind(".dcurve-partial-", 0) == 0 || it->path() == fs::path(output);
  EXPECT_EQ(left, 0u);
}

}  // namespace
}  // namespace dcurve::test
