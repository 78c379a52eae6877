// The CLI contract: --help everywhere, exit 2 on bad usage, exit 1 with a message naming the
// file on bad input, and no partial output file after a failure.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "encoder/io/files.h"
#include "encoder/io/frames.h"
#include "encoder/io/output_file.h"
#include "corpus/sim/simulation.h"
#include "cli_util.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

TEST(Cli, HelpWorksForEverySubcommand) {
  EXPECT_EQ(run_cli("--help").exit_code, 0);
  for (const char* sub : {"simulate", "encode", "decode", "info", "bench"}) {
    CommandResult r = run_cli(std::string(sub) + " --help");
    EXPECT_EQ(r.exit_code, 0) << sub;
    EXPECT_NE(r.output.find("Usage"), std::string::npos) << sub;
  }
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(run_cli("").exit_code, 2);
  EXPECT_EQ(run_cli("frobnicate").exit_code, 2);
  EXPECT_EQ(run_cli("encode").exit_code, 2);                                // missing input
  EXPECT_EQ(run_cli("encode x -o y --tolerance 7").exit_code, 2);          // out of range
  EXPECT_EQ(run_cli("encode x -o y --segment-frames often").exit_code, 2);  // neither auto nor a count
  EXPECT_EQ(run_cli("encode x -o y --effort 4").exit_code, 2);             // out of range
  EXPECT_EQ(run_cli("encode x -o y --reorder-faces --keep-face-order").exit_code, 2);  // contradictory
  EXPECT_EQ(run_cli("decode a.dcrv -o d --frames 3 --t 0.5").exit_code, 2);  // exclusive options
}

// `dcurve decode --interp`: the file's rule by default, another on request; an unknown rule
// is a usage error.
TEST(Cli, DecodeInterpOverridesTheFilesRule) {
  TempDir dir;
  const std::string in = std::string(DCURVE_SOURCE_DIR) + "/format_spec/test_vectors/hermite4_chunked.dcrv";
  auto decoded = [&](const std::string& interp, const std::string& name) {
    EXPECT_EQ(run_cli("decode " + in + " -o " + dir / name + " --t 0.3" + interp).exit_code, 0);
    std::ifstream f(dir / name);
    return std::string((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  };
  const std::string file = decoded("", "file.obj"), hermite = decoded(" --interp hermite4", "h.obj"),
                    linear = decoded(" --interp linear", "l.obj");
  EXPECT_FALSE(file.empty());
  EXPECT_EQ(file, hermite);
  EXPECT_NE(file, linear);
  EXPECT_EQ(run_cli("decode " + in + " -o " + dir / "x.obj --t 0.3 --interp cubic9").exit_code, 2);
}

TEST(Cli, MissingInputExitsOneAndNamesTheFile) {
  TempDir dir;
  CommandResult r = run_cli("encode /nonexistent/frames -o " + dir / "out.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("/nonexistent/frames"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.dcrv"));
}

// `dcurve simulate`: usage errors exit 2, bad scenes exit 1 naming the file, and the frames
// written carry the input surface (not the tet mesh).
TEST(Cli, SimulateCommandLine) {
  TempDir dir;
  CommandResult r = run_cli("simulate --list");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.output.rfind("rope-small\n", 0), 0u) << r.output;
  EXPECT_EQ(run_cli("simulate -o " + dir / "x").exit_code, 2);  // neither a file nor --scene
  EXPECT_EQ(run_cli("simulate a.json --scene rope-small -o " + dir / "x").exit_code, 2);  // both
  r = run_cli("simulate " + dir / "nope.json" + " -o " + dir / "x");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("nope.json"), std::string::npos) << r.output;
  EXPECT_EQ(run_cli("simulate --scene nope -o " + dir / "x").exit_code, 1);
  // An open surface (an octahedron missing a face) is bad input, not a crash.
  std::ofstream(dir / "open.obj") << "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n"
                                     "f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\n";
  std::ofstream(dir / "open.json") << R"({"mesh": {"file": "open.obj"}})";
  r = run_cli("simulate " + dir / "open.json" + " -o " + dir / "x");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("open.obj"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("not closed"), std::string::npos) << r.output;
  r = run_cli("simulate --scene cantilever --frames 3 -o " + dir / "out");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir / "out/frame_00000.obj"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out/frame_00002.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out/frame_00003.obj"));
  Animation anim;
  std::string err;
  ASSERT_TRUE(read_frame_folder(dir / "out", &anim, &err)) << err;
  Scene s;
  ASSERT_TRUE(builtin_scene("cantilever", &s, &err));
  std::vector<double> xyz;
  std::vector<uint32_t> faces;
  ASSERT_TRUE(load_scene_surface(s, &xyz, &faces, &err));
  EXPECT_EQ(anim.vertex_count, xyz.size() / 3);
  EXPECT_EQ(anim.faces, faces);
}

TEST(Cli, MismatchedFramesAreRejectedWithoutPartialOutput) {
  TempDir dir;
  std::filesystem::create_directory(dir / "frames");
  std::ofstream(dir / "frames/a.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::ofstream(dir / "frames/b.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 4 3\n";
  CommandResult r = run_cli("encode " + dir / "frames" + " -o " + dir / "out.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("b.obj"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.dcrv"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
}

// OpenMesh's text readers do not fail on a value they cannot parse (the OBJ reader drops the
// vertex, OFF and PLY read zeros from there on): the encoder must reject the file, naming
// the line, instead of encoding a different mesh.
TEST(Cli, NonFiniteCoordinatesAreRejected) {
  for (const std::string ext : {"obj", "off", "ply"}) {
    TempDir dir;
    std::filesystem::create_directory(dir / "frames");
    std::ofstream(dir / ("frames/a." + ext)) << square(ext, "1 0 0");
    std::ofstream(dir / ("frames/b." + ext)) << square(ext, "1 0.5 0");
    EXPECT_EQ(run_cli("encode " + dir / "frames" + " -o " + dir / "good.dcrv").exit_code, 0) << ext;
    const size_t line = square_second_vertex_line(ext);
    for (const char* bad : {"nan 0 0", "1 inf 0", "1 0 1e999", "1e39 0 0", "1 x 0"}) {
      std::ofstream(dir / ("frames/b." + ext)) << square(ext, bad);
      CommandResult r = run_cli("encode " + dir / "frames" + " -o " + dir / "out.dcrv");
      EXPECT_EQ(r.exit_code, 1) << ext << " " << bad;
      EXPECT_NE(r.output.find("b." + ext + ": line " + std::to_string(line)), std::string::npos)
          << ext << " " << bad << ": " << r.output;
      EXPECT_FALSE(std::filesystem::exists(dir / "out.dcrv")) << ext << " " << bad;
    }
  }
}

TEST(Cli, CorruptFileIsRejectedByDecodeAndInfo) {
  TempDir dir;
  std::ofstream(dir / "bad.dcrv") << "DCRV this is not a real file";
  for (const char* sub : {"info", "decode"}) {
    CommandResult r = run_cli(std::string(sub) + " " + dir / "bad.dcrv" + (std::string(sub) == "decode" ? " -o " + dir / "out" : ""));
    EXPECT_EQ(r.exit_code, 1) << sub;
    EXPECT_NE(r.output.find("bad.dcrv"), std::string::npos) << r.output;
  }
}

// `dcurve info` on the format's test vectors: the figures it prints are the recipe's, and a
// damaged file is refused with the path in the message and exit status 1.
TEST(Cli, InfoDescribesTestVectorsAndRefusesDamage) {
  const std::string vectors = std::string(DCURVE_SOURCE_DIR) + "/format_spec/test_vectors/";
  CommandResult r = run_cli("info --json " + vectors + "pde_segments.dcrv");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* key : {"\"vertices\":6", "\"frames\":9", "\"faces\":4", "\"pde8\":12", "\"pde32\":3",
                          "\"version\":\"3.2\"", "\"mode\":\"displacement\""})
    EXPECT_NE(r.output.find(key), std::string::npos) << key << " in " << r.output;
  EXPECT_NE(r.output.find("\"inbetween\":\"linear\""), std::string::npos) << r.output;
  r = run_cli("info --json " + vectors + "hermite4_chunked.dcrv");
  EXPECT_NE(r.output.find("\"inbetween\":\"hermite4\""), std::string::npos) << r.output;
  r = run_cli("info --json " + vectors + "sheet_traversal_faces.dcrv");
  EXPECT_NE(r.output.find("\"face_layout\":\"traversal\""), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"faces\":72"), std::string::npos) << r.output;
  r = run_cli("info --json " + vectors + "sheet_compact_faces.dcrv");
  EXPECT_NE(r.output.find("\"face_layout\":\"compact\""), std::string::npos) << r.output;

  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(read_file(vectors + "frames_only.dcrv", &bytes, &err)) << err;
  bytes[bytes.size() / 2] ^= 0x10;
  TempDir dir;
  ASSERT_TRUE(write_file_atomic(dir / "damaged.dcrv", bytes.data(), bytes.size(), &err)) << err;
  r = run_cli("info " + dir / "damaged.dcrv");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find(dir / "damaged.dcrv"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("checksum"), std::string::npos) << r.output;
}

TEST(Cli, EncodeDecodeInfoEndToEnd) {
  if (!have_corpus_ext()) GTEST_SKIP() << "corpus-ext not found";
  TempDir dir;
  Animation anim = read_corpus_frames("cloth-sphere", 6, 20);
  // Triangles shuffled (a fixed permutation): a face list unlike the coder's order, to keep.
  const size_t T = anim.faces.size() / 3;
  std::vector<uint32_t> shuffled;
  for (size_t i = 0; i < T; ++i) {
    const size_t from = (i * 7919) % T;  // 7919 is prime and does not divide T
    shuffled.insert(shuffled.end(), anim.faces.begin() + 3 * from, anim.faces.begin() + 3 * from + 3);
  }
  ASSERT_NE(T % 7919, 0u);
  anim.faces = shuffled;
  std::string err;
  ASSERT_TRUE(write_frame_folder(dir / "in", anim, "obj", &err)) << err;
  // A given grid skips the grid trials (tested in encode_guarantee_test), four encodes here.
  CommandResult e = run_cli("encode " + dir / "in" + " -o " + dir / "c.dcrv --tolerance 1e-3 --grid 1.5 --json");
  ASSERT_EQ(e.exit_code, 0) << e.output;
  EXPECT_NE(e.output.find("\"max_error\""), std::string::npos);
  EXPECT_NE(e.output.find("\"effort\":2"), std::string::npos) << e.output;  // the default
  CommandResult i = run_cli("info " + dir / "c.dcrv --json");
  ASSERT_EQ(i.exit_code, 0) << i.output;
  EXPECT_NE(i.output.find("\"vertices\":2500"), std::string::npos) << i.output;
  // The rate control's predictor choices are reported, one per frame and axis.
  const nlohmann::json info = nlohmann::json::parse(i.output);
  int choices = 0;
  for (const auto& [kind, count] : info["residual"]["predictors"]["kind"].items()) choices += count.get<int>();
  EXPECT_EQ(choices, 6 * 3) << i.output;
  ASSERT_EQ(run_cli("decode " + dir / "c.dcrv -o " + dir / "out").exit_code, 0);
  Animation back;
  ASSERT_TRUE(read_frame_folder(dir / "out", &back, &err)) << err;
  ASSERT_EQ(back.frames.size(), anim.frames.size());
  // Default: the same triangles, each with its winding (its corners rotated at most), in the
  // face coder's order; the shuffled list is not that order.
  EXPECT_EQ(canonical_triangles(back.faces), canonical_triangles(anim.faces));
  EXPECT_NE(back.faces, anim.faces);
  EXPECT_EQ(info["face_order"], "coder") << i.output;
  // --keep-face-order: the exact index buffer, order and first corners included, at a cost
  // that -v and info state. Only the faces matter here: no low-rank screening.
  const std::string keep = " -o " + dir / "x.dcrv --keep-face-order --grid 1.5 --low-rank off -v";
  CommandResult x = run_cli("encode " + dir / "in" + keep);
  ASSERT_EQ(x.exit_code, 0) << x.output;
  EXPECT_NE(x.output.find("faces: 4802 triangles in the order given (the exact index buffer)"), std::string::npos)
      << x.output;
  ASSERT_EQ(run_cli("decode " + dir / "x.dcrv -o " + dir / "xout --frames 1").exit_code, 0);
  Animation kept;
  ASSERT_TRUE(read_frame_folder(dir / "xout", &kept, &err)) << err;
  EXPECT_EQ(kept.faces, anim.faces);
  CommandResult xi = run_cli("info " + dir / "x.dcrv --json");
  ASSERT_EQ(xi.exit_code, 0) << xi.output;
  const nlohmann::json kept_info = nlohmann::json::parse(xi.output);
  EXPECT_EQ(kept_info["face_order"], "exact");
  // What the coder's order would take is what the default file's FACE section takes.
  EXPECT_EQ(kept_info["coder_order_connectivity_bytes"], info["connectivity_bytes"]) << xi.output;
  EXPECT_GT(kept_info["connectivity_bytes"].get<int>(), info["connectivity_bytes"].get<int>());
  ASSERT_EQ(run_cli("decode " + dir / "c.dcrv -o " + dir / "one --t 0.5 --format ply").exit_code, 0);
  EXPECT_TRUE(std::filesystem::exists(dir / "one/frame_00000.ply"));
  // A PDE model whose motions do not pay leaves the file no larger than without one.
  CommandResult p = run_cli("encode " + dir / "in" + " -o " + dir / "p.dcrv --model pde --segment-frames auto --grid 1.5 --json");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  const nlohmann::json with = nlohmann::json::parse(p.output), without = nlohmann::json::parse(e.output);
  EXPECT_GT(with["motions_fitted"].get<int>(), 0);
  EXPECT_LE(with["motions_kept"].get<int>(), with["motions_fitted"].get<int>());
  EXPECT_LE(with["bytes"].get<int>(), without["bytes"].get<int>());
  EXPECT_DOUBLE_EQ(without["grid_refinement"].get<double>(), 1.5);
}

// With stderr not a terminal (a pipe here), encode prints a plain line every interval with
// the stage, the percent done and, once known, the time left; -q silences it.
TEST(Cli, ProgressLinesWhenStderrIsAPipe) {
  TempDir dir;
  std::string err;
  ASSERT_TRUE(write_frame_folder(dir / "in", simulate_builtin("cantilever", 12), "obj", &err)) << err;
  const std::string args = "encode " + dir / "in" + " -o " + dir / "c.dcrv --threads 1 --force";
  CommandResult r = run_cli(args, 0.02);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::regex line(R"(^dcurve encode: encode (\d+)%, \d+ s(, about \d+ s left)?$)");
  int lines = 0, last = -1;
  bool monotonic = true;
  std::istringstream text(r.output);
  for (std::string l; std::getline(text, l);) {
    std::smatch m;
    if (!std::regex_match(l, m, line)) continue;
    ++lines;
    monotonic = monotonic && std::stoi(m[1]) >= last;
    last = std::stoi(m[1]);
  }
  EXPECT_GE(lines, 2) << r.output;
  EXPECT_TRUE(monotonic) << r.output;
  EXPECT_EQ(last, 100) << r.output;  // the stage's end is in the log too
  r = run_cli(args + " -q", 0.02);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output, "");
}

// `dcurve info` names the model and the face layout in words; the counts behind them come
// with -v.
TEST(Cli, InfoNamesTheModelAndFaceLayout) {
  TempDir dir;
  std::string err;
  ASSERT_TRUE(write_frame_folder(dir / "in", simulate_builtin("cantilever", 8), "obj", &err)) << err;
  const std::string in = "encode " + dir / "in" + " --grid 2 -q -o ";
  ASSERT_EQ(run_cli(in + dir / "none.dcrv --low-rank off").exit_code, 0);
  ASSERT_EQ(run_cli(in + dir / "lr.dcrv --low-rank 2").exit_code, 0);
  ASSERT_EQ(run_cli(in + dir / "pde.dcrv --low-rank off --model pde8 --keep-all-motions").exit_code, 0);
  CommandResult r = run_cli("info " + dir / "none.dcrv");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("model: none: each frame is predicted from decoded frames"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("in the face coder's order"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("motions:"), std::string::npos) << r.output;  // the counts only with -v
  EXPECT_NE(run_cli("info -v " + dir / "none.dcrv").output.find("motions: "), std::string::npos);
  r = run_cli("info " + dir / "lr.dcrv");
  EXPECT_NE(r.output.find("model: low-rank basis of 2 components"), std::string::npos) << r.output;
  r = run_cli("info " + dir / "pde.dcrv");
  EXPECT_NE(r.output.find("model: PDE curves ("), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(" pde8 and 0 pde32 motions"), std::string::npos) << r.output;
  EXPECT_EQ(nlohmann::json::parse(run_cli("info --json " + dir / "pde.dcrv").output)["model"], "pde8");
}

}  // namespace
}  // namespace dcurve::test
