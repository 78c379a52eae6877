// The bench's figures must be real: Draco errors recomputed independently from libdraco's
// own decode, every method within the tolerance it claims, the CLI's outputs well formed.
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/mesh.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>


#include "bench/baselines.h"
#include "bench/inbetween_bench.h"
#include "bench/draco_per_frame.h"
#include "bench/plot.h"
#include "bench/report.h"
#include "bench/runner.h"
#include "encoder/encoder.h"
#include "encoder/metrics.h"
#include "cli_util.h"
#include "test_util.h"

namespace dcurve::bench {
namespace {

// An n x n sheet (two triangles per cell) waving and drifting over `frames` frames.
Animation waving_sheet(int n, int frames) {
  Animation a;
  a.vertex_count = uint32_t(n * n);
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const uint32_t v = uint32_t(i * n + j);
      a.faces.insert(a.faces.end(), {v, v + 1, v + uint32_t(n), v + 1, v + uint32_t(n) + 1, v + uint32_t(n)});
    }
  for (int f = 0; f < frames; ++f) {
    std::vector<float> xyz;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x = double(j) / (n - 1), y = double(i) / (n - 1);
        xyz.push_back(float(x + 0.01 * f));
        xyz.push_back(float(y));
        xyz.push_back(float(0.2 * std::sin(3 * x + 0.4 * f) * std::cos(2 * y)));
      }
    a.frames.push_back(xyz);
  }
  return a;
}

// Independent of the bench's vertex matching: encode the frame with a generic attribute
// holding each vertex's index (a different Draco traversal, the same position quantization),
// decode, and read every decoded point's position against the vertex it names.
std::vector<float> decode_with_index_attribute(const Animation& a, size_t f, int bits) {
  const uint32_t V = a.vertex_count;
  draco::Mesh mesh;
  mesh.set_num_points(V);
  draco::GeometryAttribute pos, idx;
  pos.Init(draco::GeometryAttribute::POSITION, nullptr, 3, draco::DT_FLOAT32, false, 12, 0);
  idx.Init(draco::GeometryAttribute::GENERIC, nullptr, 1, draco::DT_UINT32, false, 4, 0);
  const int pos_id = mesh.AddAttribute(pos, true, V), idx_id = mesh.AddAttribute(idx, true, V);
  for (uint32_t v = 0; v < V; ++v) {
    mesh.attribute(pos_id)->SetAttributeValue(draco::AttributeValueIndex(v), &a.frames[f][3 * v]);
    mesh.attribute(idx_id)->SetAttributeValue(draco::AttributeValueIndex(v), &v);
  }
  for (size_t t = 0; t < a.faces.size() / 3; ++t)
    mesh.AddFace({draco::PointIndex(a.faces[3 * t]), draco::PointIndex(a.faces[3 * t + 1]),
                  draco::PointIndex(a.faces[3 * t + 2])});
  draco::Encoder enc;
  enc.SetSpeedOptions(0, 0);
  enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, bits);
  draco::EncoderBuffer out;
  EXPECT_TRUE(enc.EncodeMeshToBuffer(mesh, &out).ok());
  draco::DecoderBuffer in;
  in.Init(out.data(), out.size());
  draco::Decoder dec;
  auto decoded = std::move(dec.DecodeMeshFromBuffer(&in)).value();
  std::vector<float> xyz(size_t(V) * 3, NAN);
  const auto* p = decoded->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  const auto* id = decoded->GetNamedAttribute(draco::GeometryAttribute::GENERIC);
  for (draco::PointIndex q(0); q < decoded->num_points(); ++q) {
    uint32_t v = 0;
    id->GetMappedValue(q, &v);
    p->GetMappedValue(q, &xyz[3 * size_t(v)]);
  }
  return xyz;
}

double own_max_error(const std::vector<float>& ref, const std::vector<float>& got, double L) {
  double worst = 0;
  for (size_t v = 0; v < ref.size() / 3; ++v) {
    double d2 = 0;
    for (int c = 0; c < 3; ++c) d2 += std::pow(double(got[3 * v + c]) - ref[3 * v + c], 2);
    worst = std::max(worst, std::sqrt(d2));
  }
  return worst / L;
}

// The positions a Draco file holds, as libdraco decodes them, sorted (order-free).
std::vector<std::array<float, 3>> sorted_positions(const std::vector<char>& file) {
  draco::DecoderBuffer in;
  in.Init(file.data(), file.size());
  draco::Decoder dec;
  auto mesh = std::move(dec.DecodeMeshFromBuffer(&in)).value();
  const auto* p = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
  std::vector<std::array<float, 3>> out(mesh->num_points());
  for (draco::PointIndex q(0); q < mesh->num_points(); ++q) p->GetMappedValue(q, out[q.value()].data());
  std::sort(out.begin(), out.end());
  return out;
}

void check_draco_per_frame(const Animation& a, double tol) {
  const double L = bbox_diagonal(a.frames[0]);
  DracoFrameCodec draco;
  std::string err;
  ASSERT_TRUE(draco.init(a.vertex_count, a.faces, &err)) << err;
  const BenchContext ctx{a, tol, L, draco, draco.connectivity_bytes(), EncodeOptions().effort};
  DracoPerFrameChoice choice;
  ASSERT_TRUE(choose_draco_per_frame(ctx, &choice, &err)) << err;
  ASSERT_TRUE(choice.all_meet);
  for (size_t f = 0; f < a.frames.size(); ++f) {
    const std::vector<float> indep = decode_with_index_attribute(a, f, choice.bits[f]);
    // The file the bench counted holds exactly the positions the independent decode saw.
    std::vector<std::array<float, 3>> expect(a.vertex_count);
    for (size_t v = 0; v < expect.size(); ++v) expect[v] = {indep[3 * v], indep[3 * v + 1], indep[3 * v + 2]};
    std::sort(expect.begin(), expect.end());
    std::vector<std::array<float, 3>> got = sorted_positions(choice.files[f]);
    got.erase(std::unique(got.begin(), got.end()), got.end());
    expect.erase(std::unique(expect.begin(), expect.end()), expect.end());
    EXPECT_EQ(got, expect) << "frame " << f;
    const double own = own_max_error(a.frames[f], indep, L);
    EXPECT_NEAR(choice.max_error[f], own, 1e-12) << "frame " << f;
    EXPECT_LE(choice.max_error[f], tol);
    // Smallest bits: one bit fewer misses the tolerance.
    if (choice.bits[f] > kDracoMinBits) {
      EXPECT_GT(own_max_error(a.frames[f], decode_with_index_attribute(a, f, choice.bits[f] - 1), L), tol)
          << "frame " << f;
    }
  }
}

TEST(BenchDraco, PerFrameErrorEqualsIndependentRecomputation) {
  check_draco_per_frame(waving_sheet(14, 4), 1e-3);
}

TEST(BenchDraco, PerFrameErrorOnRealSequence) {
  const std::string dir = std::string(DCURVE_CORPUS_EXT) + "/chicken-crossing";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no corpus-ext";
  // Three frames: 41 components, a real edgebreaker case, still fast.
  Animation a;
  std::string err;
  for (int f = 0; f < 3; ++f) {
    std::vector<float> xyz;
    ASSERT_TRUE(read_mesh(dir + "/frame_0000" + std::to_string(f) + ".obj", &xyz, &a.faces, &err)) << err;
    a.frames.push_back(xyz);
  }
  a.vertex_count = uint32_t(a.frames[0].size() / 3);
  check_draco_per_frame(a, 1e-3);
}

TEST(BenchDraco, RejectsVertexOnNoTriangle) {
  Animation a = waving_sheet(5, 2);
  a.vertex_count += 1;
  for (auto& f : a.frames) f.insert(f.end(), {2.f, 2.f, 2.f});
  DracoFrameCodec draco;
  std::string err;
  EXPECT_FALSE(draco.init(a.vertex_count, a.faces, &err));
  EXPECT_NE(err.find("vertex 25"), std::string::npos) << err;
}

TEST(BenchRunner, EveryMethodKeepsItsClaims) {
  const Animation a = waving_sheet(12, 6);
  const double tol = 2e-3;
  const InputResult r = run_bench("sheet", a, tol, nullptr);
  ASSERT_EQ(r.methods.size(), all_methods().size());
  EXPECT_EQ(r.vertices, a.vertex_count);
  EXPECT_EQ(r.frames, 6u);
  for (const auto& m : r.methods) {
    SCOPED_TRACE(m.method + ": " + m.settings);
    EXPECT_TRUE(m.meets_tolerance);
    EXPECT_LE(m.max_error, tol);
    EXPECT_LE(m.rmse, m.max_error);
    EXPECT_GT(m.bytes, m.connectivity_bytes);
    EXPECT_NEAR(m.bpvf, 8.0 * m.bytes / (a.vertex_count * 6.0), 1e-9);
    EXPECT_GT(m.decode_vertices_per_second, 0);
  }
  const auto find = [&](const std::string& name) {
    return *std::find_if(r.methods.begin(), r.methods.end(), [&](const MethodResult& m) { return m.method == name; });
  };
  EXPECT_EQ(find("raw_float32").max_error, 0);
  EXPECT_EQ(find("raw_float32").bytes, a.vertex_count * 6u * 12u + find("raw_float32").connectivity_bytes);
  EXPECT_EQ(find("raw_zstd").max_error, 0);
  EXPECT_DOUBLE_EQ(ratio_to_draco_per_frame(r, find("draco_per_frame")), 1.0);
  // Draco per frame pays connectivity in every frame; the others once, the same charge.
  EXPECT_EQ(find("draco_per_frame").connectivity_bytes, 6 * find("pca").connectivity_bytes);
  EXPECT_EQ(find("quantized_delta").connectivity_bytes, find("pca").connectivity_bytes);
  std::string best;
  const double to_best = ratio_to_best_other(r, find("dcurve"), &best);
  EXPECT_NE(best, "dcurve");
  EXPECT_NEAR(to_best, double(find("dcurve").bytes) / double(find(best).bytes), 1e-12);
  for (const auto& m : r.methods) {
    if (m.method == "dcurve") continue;
    EXPECT_GE(m.bytes, find(best).bytes) << m.method;
  }
  const std::string table = format_table({r});
  for (const auto& name : all_methods()) EXPECT_NE(table.find(name), std::string::npos) << name;
}

TEST(BenchRunner, PcaFindsFewComponentsForRankOneMotion) {
  Animation a = waving_sheet(10, 8);
  // Every frame = rest + s(f) * one fixed displacement field: one component is exact.
  for (size_t f = 1; f < a.frames.size(); ++f)
    for (size_t i = 0; i < a.frames[f].size(); ++i)
      a.frames[f][i] = a.frames[0][i] + float(std::sin(0.7 * f)) * 0.1f * float(i % 7) / 7.f;
  const InputResult r = run_bench("rank1", a, 1e-3, {"pca"}, nullptr);
  ASSERT_EQ(r.methods.size(), 1u);
  EXPECT_TRUE(r.methods[0].meets_tolerance) << r.methods[0].settings;
  EXPECT_EQ(r.methods[0].settings.rfind("k=1 ", 0), 0u) << r.methods[0].settings;
}

TEST(BenchRunner, SingleFrameRunsEveryMethod) {
  const InputResult r = run_bench("one", waving_sheet(6, 1), 1e-3, nullptr);
  for (const auto& m : r.methods) EXPECT_TRUE(m.meets_tolerance) << m.method << ": " << m.settings;
}

TEST(BenchRunner, RejectsUnknownMethodAndBadTolerance) {
  const Animation a = waving_sheet(4, 2);
  EXPECT_THROW(run_bench("x", a, 1e-3, {"zip"}, nullptr), std::invalid_argument);
  EXPECT_THROW(run_bench("x", a, 0.0, nullptr), std::invalid_argument);
  EXPECT_THROW(run_bench("x", a, 1e-3, {"dcurve"}, nullptr, 4), std::invalid_argument);
}

TEST(BenchPlot, OnePanelPerInputAndOneMarkerPerResult) {
  InputResult a{"first", 1e-3, 10, 2, {{"m1", 100, 10, 40, 1e-3, 5e-4, 1, 0, 0, true, ""},
                                      {"m2", 200, 10, 80, 0, 0, 0, 0, 0, true, ""}}};
  InputResult b = a;
  b.input = "second&<b>";
  InputResult c = a;
  c.tolerance = 1e-2;
  c.methods[0].max_error = 8e-3;
  c.methods[0].meets_tolerance = false;
  const std::string svg = rate_distortion_svg({a, b, c});
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  auto count = [&](const std::string& s) {
    size_t n = 0;
    for (size_t p = svg.find(s); p != std::string::npos; p = svg.find(s, p + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("font-weight='bold'"), 2u);  // two distinct inputs
  EXPECT_NE(svg.find("second&amp;&lt;b&gt;"), std::string::npos);
  EXPECT_EQ(count("<circle"), 6u + 4u);        // 6 results + 2 legend entries per panel
  EXPECT_EQ(count("stroke-width='1.5' fill='white'"), 1u);  // the one result that missed its tolerance
}

// Output through a pipe, not a shared file: ctest runs these tests in parallel.
std::string run_cli(const std::string& args, int* status) {
  dcurve::test::CommandResult r = dcurve::test::run_cli("bench " + args);
  *status = r.exit_code;
  return r.output;
}

TEST(BenchCli, JsonCsvAndPlotFromFrameFolder) {
  const std::string dir = testing::TempDir() + "/bench_cli_sheet";
  std::filesystem::remove_all(dir);
  std::string err;
  ASSERT_TRUE(write_frame_folder(dir, waving_sheet(8, 3), "obj", &err)) << err;
  const std::string csv = testing::TempDir() + "/bench.csv", svg = testing::TempDir() + "/bench.svg";
  int status = 0;
  const std::string out = run_cli(dir + " --tolerance 1e-2 --tolerance 1e-3 --methods dcurve,quantized_delta --effort 1 " +
                                      "--json --csv " + csv + " --plot " + svg,
                                  &status);
  ASSERT_EQ(status, 0) << out;
  const nlohmann::json j = nlohmann::json::parse(out);
  ASSERT_EQ(j["results"].size(), 2u);
  EXPECT_EQ(j["results"][0]["input"], "bench_cli_sheet");
  EXPECT_EQ(j["results"][1]["tolerance"], 1e-3);
  ASSERT_EQ(j["results"][0]["methods"].size(), 2u);
  for (const char* key : {"method", "bytes", "connectivity_bytes", "motion_bytes", "ratio_to_draco_per_frame",
                          "ratio_to_best_other", "bpvf", "max_error", "rmse", "kg_error_pct", "encode_seconds",
                          "decode_vertices_per_second", "meets_tolerance", "settings"})
    EXPECT_TRUE(j["results"][0]["methods"][0].contains(key)) << key;
  EXPECT_TRUE(j["results"][0]["methods"][0]["ratio_to_draco_per_frame"].is_null());  // Draco not run
  // dcurve ran at the effort asked for: the file `dcurve encode --effort 1` writes.
  Animation sheet;
  ASSERT_TRUE(read_frame_folder(dir, &sheet, &err)) << err;
  EncodeOptions effort1;
  effort1.tolerance = 1e-2;
  effort1.effort = 1;
  std::vector<uint8_t> bytes;
  ASSERT_TRUE(encode_animation(sheet, effort1, &bytes, nullptr, &err)) << err;
  EXPECT_EQ(j["results"][0]["methods"][0]["bytes"], bytes.size());
  EXPECT_NE(j["results"][0]["methods"][0]["settings"].get<std::string>().find("effort=1"), std::string::npos);
  std::ifstream c(csv);
  std::string line;
  int lines = 0;
  while (std::getline(c, line)) ++lines;
  EXPECT_EQ(lines, 1 + 4);
  EXPECT_TRUE(std::filesystem::file_size(svg) > 100);
}

TEST(BenchCli, BadInputsFailClearly) {
  int status = 0;
  std::string out = run_cli("/nonexistent/folder", &status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find("/nonexistent/folder"), std::string::npos) << out;
  out = run_cli("--methods zip " + testing::TempDir(), &status);
  EXPECT_EQ(status, 2) << out;
  out = run_cli("--effort 0 " + testing::TempDir(), &status);
  EXPECT_EQ(status, 2) << out;
  out = run_cli("--protocol paper2024 " + testing::TempDir(), &status);
  EXPECT_EQ(status, 1);
  EXPECT_NE(out.find("no .obj, .ply or .off frames"), std::string::npos) << out;
  out = run_cli("--protocol paper2024", &status);
  EXPECT_EQ(status, 2) << out;
}

// The in-between bench on a sheet whose every vertex moves on a parabola in time: the stored
// frames decode within the tolerance, Catmull-Rom through the true even frames is exact
// (it reproduces quadratics, end frames included) and linear blending is not.
TEST(BenchInbetween, StoredWithinToleranceAndCatmullRomExactOnParabolas) {
  Animation a = waving_sheet(6, 9);
  for (size_t f = 0; f < a.frames.size(); ++f)
    for (size_t i = 0; i < a.frames[f].size(); ++i)
      a.frames[f][i] = float(a.frames[0][i] + 0.003 * double(f * f) * (1 + double(i % 3)));
  EncodeOptions options;
  options.tolerance = 1e-3;
  InbetweenResult r;
  std::string error;
  ASSERT_TRUE(run_inbetween_bench("parabolas", a, options, false, &r, &error)) << error;
  EXPECT_EQ(r.held_out, 4u);
  EXPECT_GT(r.plain.rmse_stored, 0.0);
  EXPECT_LE(r.plain.rmse_stored, options.tolerance);
  EXPECT_LT(r.true_rmse[uint8_t(Inbetween::CatmullRom)], 1e-6);
  EXPECT_GT(r.true_rmse[uint8_t(Inbetween::Linear)], 1e-3);
  EXPECT_EQ(r.plain.rmse_recorded, r.plain.rmse[uint8_t(r.plain.recorded)]);
}

}  // namespace
}  // namespace dcurve::bench
