// Hostile .dcrv files through the dcurve program (issue 59, decode side): materials nested
// past any glTF end in a clear error naming the file, whatever the output parses them for,
// and `info` summarises many face groups instead of printing every name.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_util.h"
#include "encoder/encoder.h"
#include "encoder/io/output_file.h"
#include "test_util.h"

namespace dcurve::test {
namespace {

// A 3 x 3 sheet over two frames with render vertices, in `groups` face groups (named "g0",
// "g1", ...; the triangles in the first two), with `materials` as MATL's JSON, written to `path`.
void write_grouped_sheet(const std::string& path, uint32_t groups, const std::string& materials) {
  Animation a;
  a.vertex_count = 9;
  a.faces = grid_faces(3, 3);
  for (int f = 0; f < 2; ++f) {
    a.frames.emplace_back();
    for (uint32_t v = 0; v < 9; ++v) a.frames.back().insert(a.frames.back().end(), {float(v % 3), float(v / 3), 0.2f * f});
  }
  for (uint32_t v = 0; v < 9; ++v) a.render.source.push_back(v);
  a.render.corners = a.faces;
  for (uint32_t g = 0; g < groups; ++g) a.render.groups.push_back({-1, "g" + std::to_string(g)});
  for (uint32_t t = 0; t < 8; ++t) a.render.face_group.push_back(t % 2);
  a.materials.json = materials;
  std::vector<uint8_t> bytes;
  std::string err;
  ASSERT_TRUE(encode_animation(a, EncodeOptions(), &bytes, nullptr, &err)) << err;
  ASSERT_TRUE(write_file_atomic(path, bytes.data(), bytes.size(), &err)) << err;
}

TEST(CliHostileRender, DeeplyNestedMaterialsAreAnErrorNamingTheFile) {
  TempDir dir;
  const std::string input = dir / "deep.dcrv";
  write_grouped_sheet(input, 2, "{\"materials\":" + std::string(100000, '[') + std::string(100000, ']') + "}");
  for (const std::string output : {"o.glb", "o.gltf", "o.obj --t 0", "frames/"}) {
    const CommandResult r = run_cli_command("timeout 60 " + cli_program() + " decode " + input + " -o " + (dir / output));
    EXPECT_EQ(r.exit_code, 1) << output << ": " << r.output;
    EXPECT_TRUE(contains(r.output, input + ": its materials (MATL): JSON nested deeper than 128")) << r.output;
  }
  // An output that does not parse the materials decodes.
  const CommandResult pc2 = run_cli_command(cli_program() + " decode " + input + " -o " + (dir / "o.pc2"));
  EXPECT_EQ(pc2.exit_code, 0) << pc2.output;
}

TEST(CliHostileRender, InfoSummarisesManyFaceGroups) {
  TempDir dir;
  write_grouped_sheet(dir / "many.dcrv", 1000, "");
  const CommandResult r = run_cli("info " + (dir / "many.dcrv"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::istringstream lines(r.output);
  std::string groups;
  for (std::string line; std::getline(lines, line);)
    if (contains(line, "face groups")) groups = line;
  EXPECT_TRUE(contains(groups, "1000 face groups (materials \"g0\", \"g1\", \"g2\", \"g3\", \"g4\" and 995 more)")) << groups;
  EXPECT_LT(r.output.size(), 2000u);
  const CommandResult j = run_cli("info --json " + (dir / "many.dcrv"));
  EXPECT_TRUE(contains(j.output, "\"g999\"")) << "--json lists every group";
}

}  // namespace
}  // namespace dcurve::test
