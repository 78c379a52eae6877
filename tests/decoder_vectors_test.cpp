// The test vectors of format_spec/test_vectors: stored files must decode to the stored
// expected positions, the expected positions must match the spec formulas for the recipe,
// and the writer must still produce the stored bytes. A layout change cannot pass silently.
// DCURVE_WRITE_TEST_VECTORS=1 rewrites the files (after an intentional format change).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "codec/common/container_format.h"
#include "codec/common/fast_residual.h"
#include "codec/common/low_rank.h"
#include "codec/common/render_mesh.h"
#include "codec/common/residual.h"
#include "codec/compress/container_writer.h"
#include "codec/compress/faces_encoder.h"
#include "codec/compress/fast_residual_encoder.h"
#include "codec/compress/residual_encoder.h"
#include "codec/decompress/model_prediction.h"
#include "decoder/dcurve.hpp"
#include "encoder/rate/block_flags.h"
#include "test_models.h"

namespace dcurve {
namespace {

struct Vector {
  const char* name;
  Model model;
  WriteOptions options;
};

// A hand-made low-rank model (LRNK, with coefficient shifts, and with frame poses when
// `posed`: format 2.5) on `m`, and its residual re-coded with the Model predictor on every
// frame: the grid values, hence the expected positions, do not change. fast: format 4, the
// basis and the residual as fast payloads, the differences packed.
// fast_basis: 0 for a range-coded basis, else the fast payload's kind of each basis vector
// (the mean: None with the spatial flag).
Model with_low_rank(Model m, bool posed = false, uint8_t fast_basis = 0) {
  const uint32_t V = m.meta.vertex_count, F = m.meta.frame_count, K = 2;
  LowRankModel& lr = m.low_rank;
  lr.components = K;
  lr.shift = 3;
  lr.mean_shift = 1;
  // Component 1's coefficients are multiples of 4, stored divided by 4 (format 2.3).
  lr.coeff_shifts = {0, 2};
  for (uint32_t f = 0; f < F; ++f) lr.coeffs.insert(lr.coeffs.end(), {int32_t(8 * f) - 5, 4 * (int32_t(f * f) - 3)});
  std::vector<int32_t> mean_and_basis;
  for (uint32_t k = 0; k <= K; ++k)
    for (uint32_t v = 0; v < V; ++v)
      for (int a = 0; a < 3; ++a) mean_and_basis.push_back(k == 0 ? 2 * testing::grid_value(0, v, a) + 1 : int32_t(v % 4) * int32_t(k + a) - 2);
  Model pseudo = m;
  pseudo.meta.frame_count = K + 1;
  pseudo.low_rank = LowRankModel{};
  PredictorPlan spatial = uniform_plan(
      {0, 1, 2}, std::vector<PredictorChoice>(3 * (K + 1), PredictorChoice{PredictorKind::None, 0, 0, SpatialMode::Parallelogram}));
  std::vector<uint8_t> kinds(K + 1, fast_basis);
  kinds[0] = fast_residual::kSpatialFlag;
  lr.basis_payload = fast_basis ? encode_fast_residuals(pseudo, mean_and_basis, kinds, K + 1, nullptr)
                               : encode_residuals(pseudo, mean_and_basis, &spatial);
  if (posed) {
    // Not rotations (nothing requires it): a growing turn about z, a squeeze along z, a drift.
    const int32_t one = int32_t(1) << kLowRankPoseShift;
    lr.pose_centre[0] = 5;
    lr.pose_centre[1] = -6;
    lr.pose_centre[2] = 7;
    for (uint32_t f = 0; f < F; ++f) {
      const int32_t turn = int32_t(f) * 3000, i = int32_t(f);
      lr.poses.insert(lr.poses.end(), {one, -turn, 0, turn, one, 0, 0, 0, one - 500 * i, i, -2 * i, 3});
    }
  }
  std::vector<int32_t> prediction;
  std::string err;
  if (!model_grid_prediction(m, UINT64_MAX, &prediction, &err)) ADD_FAILURE() << err;
  ResidualOptions ro;
  if (fast_basis) {
    // Model alone, then Model plus spatial, then ModelDelta with spatial, over chunks of 4.
    std::vector<uint8_t> kinds;
    for (uint32_t f = 0; f < F; ++f) kinds.push_back(f % 4 == 0 ? 3 : f % 2 ? 0x13 : 0x14);
    m.residual.payload = encode_fast_residuals(m, testing::grid(V, F), kinds, 4, &prediction);
    return m;
  }
  ro.model_prediction = &prediction;
  std::vector<uint32_t> order;
  for (uint32_t f = 0; f < F; ++f) order.push_back(f);
  PredictorPlan plan =
      uniform_plan(order, std::vector<PredictorChoice>(size_t(F) * 3, PredictorChoice{PredictorKind::Model, 0, 0, SpatialMode::Mean}));
  m.residual.payload = encode_residuals(m, testing::grid(V, F), &plan, ro);
  return m;
}

std::vector<Vector> recipes() {
  using testing::add_pde_motions;
  using testing::small_model;
  using Layout = WriteOptions::FaceLayout;
  std::vector<Vector> v;
  v.push_back({"frames_only", small_model(4), {}});
  v.back().options.face_layout = Layout::Exact;

  v.push_back({"zero_segments_no_faces", testing::without_faces(small_model(5, {0, 2, 4})), {}});
  v.back().options.connectivity = false;

  Model pde = small_model(9, {0, 3, 8, 8});
  add_pde_motions(&pde, 5);
  pde.segments[1].mode = FitMode::Displacement;
  v.push_back({"pde_segments", pde, {}});

  Model sheet = testing::sheet_model(7, 4);
  sheet.faces = traversal_order(sheet.faces);
  sheet.residual.payload = encode_residuals(sheet, testing::grid(sheet.meta.vertex_count, 4));
  v.push_back({"sheet_traversal_faces", sheet, {}});
  v.back().options.face_layout = Layout::Traversal;
  // The same faces in the Compact layout: also the fuzzer's seed for that coder.
  v.push_back({"sheet_compact_faces", sheet, {}});
  v.back().options.face_layout = Layout::Compact;

  Model model_only = small_model(5, {0, 4});
  add_pde_motions(&model_only, 3);
  model_only.residual = ResidualLayer{};
  v.push_back({"model_only", model_only, {}});

  // Every frame after the first predicted from the one before with a spatial mode whose
  // weights come from that frame's shape: Geometric (format 2.1) and Fit (2.4).
  for (SpatialMode mode : {SpatialMode::Geometric, SpatialMode::Fit}) {
    Model m = testing::sheet_model(5, 6);
    m.faces = traversal_order(m.faces);
    std::vector<PredictorChoice> choices(3, PredictorChoice{PredictorKind::None, 0, 0, SpatialMode::Parallelogram, 0});
    for (uint32_t f = 1; f < 6; ++f)
      choices.insert(choices.end(), 3, PredictorChoice{PredictorKind::Reference, f - 1, 0, mode, f - 1});
    const PredictorPlan plan = uniform_plan({0, 1, 2, 3, 4, 5}, choices);
    m.residual.payload = encode_residuals(m, testing::grid(m.meta.vertex_count, 6), &plan);
    v.push_back({mode == SpatialMode::Fit ? "fit" : "geometric", m, {}});
  }

  // One-point curves and no segments: neither CURV nor SEGS is written (format 2.2).
  Model point_curves = small_model(4);
  point_curves.curves = singleton_curves(point_curves.meta.vertex_count);
  point_curves.residual.payload = encode_residuals(point_curves, testing::grid(point_curves.meta.vertex_count, 4));
  v.push_back({"point_curves", point_curves, {}});

  // Chunks of 4 frames (format 3.0): 10 frames in three chunks, the last of 2; segments that
  // cross chunk boundaries, so the blend between chunks and the model are both exercised.
  Model chunked = small_model(10, {0, 5, 9});
  add_pde_motions(&chunked, 7);
  chunked.residual.payload =
      encode_residuals(chunked, testing::grid(chunked.meta.vertex_count, 10), default_chunked_plan(10, 4));
  v.push_back({"chunked", chunked, {}});

  Model low_rank_sheet = testing::sheet_model(5, 6);
  low_rank_sheet.faces = traversal_order(low_rank_sheet.faces);
  v.push_back({"low_rank", with_low_rank(low_rank_sheet), {}});
  v.push_back({"low_rank_posed", with_low_rank(low_rank_sheet, true), {}});

  // In-between rules (format 3.2): Catmull-Rom through 7 frames without segments, and
  // Hermite4 on the chunked recipe, whose stencils reach across segment ends (one-sided
  // tangents) and chunk boundaries (frames of the neighbouring chunks).
  Model catmull_rom = small_model(7);
  catmull_rom.meta.inbetween = Inbetween::CatmullRom;
  v.push_back({"catmull_rom", catmull_rom, {}});
  Model hermite4 = chunked;
  hermite4.meta.inbetween = Inbetween::Hermite4;
  v.push_back({"hermite4_chunked", hermite4, {}});
  // Every payload as format 3.1 writes it at its smallest: with block flags (version 4).
  for (Vector& vector : v) {
    std::string err;
    EXPECT_TRUE(use_block_flags(&vector.model, BlockFlagUse::Always, &err)) << vector.name << ": " << err;
  }
  // Format 4: fast payloads (residual.md section 10) in chunks of 4, every frame kind; the
  // second on the chunked recipe, whose PDE segments give kinds 3 and 4 their Model prediction.
  Model fast_frames = small_model(7);
  fast_frames.residual.payload =
      encode_fast_residuals(fast_frames, testing::grid(6, 7), {0x10, 1, 0x32, 2, 0x30, 0x11, 2}, 4, nullptr);
  v.push_back({"fast_frames", fast_frames, {}});
  Model fast_model = chunked;
  std::vector<int32_t> prediction;
  std::string err;
  EXPECT_TRUE(model_grid_prediction(fast_model, UINT64_MAX, &prediction, &err)) << err;
  fast_model.residual.payload =
      encode_fast_residuals(fast_model, testing::grid(6, 10), {3, 0x14, 4, 1, 0x13, 4, 2, 0x14, 3, 0}, 4,
                            &prediction);
  v.push_back({"fast_model_chunked", fast_model, {}});
  // Format 4 with LRNK: a fast basis payload, packed coefficient and pose differences; then
  // (format 4.3) a basis whose vectors are predicted by Fit over the mean's shape.
  v.push_back({"fast_low_rank_posed", with_low_rank(low_rank_sheet, true, fast_residual::kSpatialFlag), {}});
  v.push_back({"fast_low_rank_fit",
               with_low_rank(low_rank_sheet, false, fast_residual::kSpatialFlag | fast_residual::kFitFlag), {}});
  // Format 3.3: render vertices (copies of vertices 3 and 1 in the last two triangles) with
  // texture coordinates and colours, and a placement (dcrv.md sections 19, 20).
  Model render = small_model(4);
  render.render.source = {0, 1, 2, 3, 4, 5, 3, 1};
  render.render.corners = {0, 1, 2, 2, 1, 3, 6, 7, 4, 4, 5, 6};
  RenderAttribute uv{AttributeSemantic::TexCoord0, 2, 10, {0.f, -1.f}, {1.f, 1.f}, {}};
  RenderAttribute color{AttributeSemantic::Color0, 4, 8, {0.f, 0.f, 0.f, 1.f}, {1.f, 0.5f, 1.f, 1.f}, {}};
  for (uint16_t r = 0; r < 8; ++r) {
    uv.q.insert(uv.q.end(), {uint16_t(100 * r), uint16_t(1023 - 50 * r)});
    color.q.insert(color.q.end(), {uint16_t(30 * r), uint16_t(255 - r), uint16_t(r * r), 0});
  }
  render.render.attributes = {uv, color};
  // Two groups, the second (triangles 1 and 3) with a textured material.
  render.render.groups = {{-1, ""}, {0, "cloth"}};
  render.render.face_group = {0, 1, 0, 1};
  render.materials.json =
      R"({"materials":[{"name":"cloth","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
      R"("textures":[{"source":0}],"samplers":[],"images":[{"mimeType":"image/png"}]})";
  render.materials.images = {{"image/png", {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 1, 2, 3}}};
  render.placement.start_time = 0.5;
  render.placement.has_matrix = true;
  render.placement.matrix[12] = 2.0;
  render.placement.matrix[0] = 0.5;
  render.placement.mesh_name = "mesh";
  render.placement.node_name = "node";
  v.push_back({"render_placement", render, {}});
  return v;
}

std::vector<double> sample_times() {
  std::vector<double> t;
  for (int k = 0; k <= 16; ++k) t.push_back(k / 16.0);
  t.push_back(0.123456789);
  return t;
}

std::string dir() { return std::string(DCURVE_SOURCE_DIR) + "/format_spec/test_vectors/"; }

std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// One line per t: t and V * 3 coordinates, from the spec formulas in double.
std::string expected_text(const Model& m) {
  std::ostringstream out;
  char buf[32];
  for (double t : sample_times()) {
    std::snprintf(buf, sizeof buf, "%.9g", t);
    out << buf;
    const double x = t * (m.meta.frame_count - 1);
    for (uint32_t v = 0; v < m.meta.vertex_count; ++v)
      for (int a = 0; a < 3; ++a) {
        std::snprintf(buf, sizeof buf, " %.9g", testing::expected_position(m, x, v, a));
        out << buf;
      }
    out << "\n";
  }
  return out.str();
}

struct ExpectedLine {
  double t = 0;
  std::vector<double> xyz;
};

std::vector<ExpectedLine> parse_expected(const std::string& text) {
  std::vector<ExpectedLine> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    ExpectedLine e;
    fields >> e.t;
    for (double x; fields >> x;) e.xyz.push_back(x);
    lines.push_back(e);
  }
  return lines;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(TestVectors, WriteWhenAsked) {
  if (!std::getenv("DCURVE_WRITE_TEST_VECTORS")) GTEST_SKIP() << "set DCURVE_WRITE_TEST_VECTORS=1 to rewrite";
  for (const Vector& v : recipes()) {
    std::vector<uint8_t> bytes = write_container(v.model, v.options);
    std::ofstream(dir() + v.name + ".dcrv", std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()),
                                                                     std::streamsize(bytes.size()));
    std::ofstream(dir() + v.name + ".expected.txt") << expected_text(v.model);
  }
}

TEST(TestVectors, WriterReproducesTheStoredBytes) {
  for (const Vector& v : recipes()) {
    std::vector<uint8_t> stored = read_bytes(dir() + v.name + ".dcrv");
    ASSERT_FALSE(stored.empty()) << "missing test vector " << v.name;
    EXPECT_EQ(write_container(v.model, v.options), stored) << v.name;
  }
}

// Compared as numbers, not text: another libm may round the last printed digit differently.
TEST(TestVectors, ExpectedFilesMatchTheSpecFormulas) {
  for (const Vector& v : recipes()) {
    std::vector<ExpectedLine> stored = parse_expected(read_text(dir() + v.name + ".expected.txt"));
    std::vector<ExpectedLine> fresh = parse_expected(expected_text(v.model));
    ASSERT_EQ(stored.size(), fresh.size()) << v.name;
    for (size_t k = 0; k < stored.size(); ++k) {
      EXPECT_EQ(stored[k].t, fresh[k].t);
      ASSERT_EQ(stored[k].xyz.size(), size_t(v.model.meta.vertex_count) * 3) << v.name;
      ASSERT_EQ(stored[k].xyz.size(), fresh[k].xyz.size()) << v.name;
      for (size_t i = 0; i < stored[k].xyz.size(); ++i)
        EXPECT_NEAR(stored[k].xyz[i], fresh[k].xyz[i], 1e-7 * (1 + std::abs(fresh[k].xyz[i]))) << v.name;
    }
  }
}

// The decoder's positions for the file at `path` against the recipe's expected file.
void expect_decodes_as_expected(const std::string& path, const std::string& name) {
  std::string err;
  auto d = Decoder::open_file(path, &err);
  ASSERT_TRUE(d) << path << ": " << err;
  std::vector<ExpectedLine> lines = parse_expected(read_text(dir() + name + ".expected.txt"));
  EXPECT_EQ(lines.size(), sample_times().size()) << name;
  std::vector<float> xyz(size_t(d->vertex_count()) * 3);
  for (const ExpectedLine& e : lines) {
    ASSERT_EQ(e.xyz.size(), xyz.size()) << path;
    d->evaluate(e.t, xyz.data());
    for (size_t i = 0; i < xyz.size(); ++i)
      EXPECT_NEAR(xyz[i], e.xyz[i], 1e-5 * (1 + std::abs(e.xyz[i]))) << path << " t " << e.t << " value " << i;
  }
}

TEST(TestVectors, DecoderReproducesTheExpectedPositions) {
  for (const Vector& v : recipes()) expect_decodes_as_expected(dir() + v.name + ".dcrv", v.name);
}

// test_vectors/3.0 and 3.1 keep the files of the recipes that existed then as those formats
// wrote them (3.0: residual payloads without block flags; both: no in-between field, so
// linear in-betweens): a 3.2 decoder reads them to the same positions.
void expect_older_files_decode(const std::string& version, uint16_t minor) {
  for (const Vector& v : recipes()) {
    if (v.model.meta.inbetween != Inbetween::Linear) continue;  // recipes of format 3.2
    const std::vector<uint8_t>& payload = v.model.residual.payload;
    if (!payload.empty() && payload[0] == fast_residual::kPayloadVersion) continue;  // format 4
    if (!v.model.render.empty() || !v.model.placement.empty()) continue;             // format 3.3
    const std::string path = dir() + version + "/" + v.name + ".dcrv";
    const std::vector<uint8_t> bytes = read_bytes(path);
    ASSERT_GE(bytes.size(), 8u) << "missing test vector " << path;
    EXPECT_EQ(bytes[4] | bytes[5] << 8, 3);  // version_major
    EXPECT_EQ(bytes[6] | bytes[7] << 8, minor);
    std::string err;
    auto d = Decoder::open_file(path, &err);
    ASSERT_TRUE(d) << path << ": " << err;
    EXPECT_EQ(d->interpolation(), Interpolation::Linear) << path;
    expect_decodes_as_expected(path, v.name);
  }
}

// The render vector's REND and PLAC decode to the recipe's values (dcrv.md sections 19, 20),
// and a 3.3 file keeps its version.
TEST(TestVectors, RenderVerticesAndPlacementDecodeAsWritten) {
  for (const Vector& v : recipes()) {
    if (v.model.render.empty()) continue;
    const std::string path = dir() + v.name + ".dcrv";
    const std::vector<uint8_t> bytes = read_bytes(path);
    ASSERT_GE(bytes.size(), 8u) << "missing test vector " << path;
    EXPECT_EQ(bytes[6] | bytes[7] << 8, kRenderFormatVersionMinor);
    std::string err;
    auto d = Decoder::open_file(path, &err);
    ASSERT_TRUE(d) << path << ": " << err;
    const RenderMesh& r = v.model.render;
    ASSERT_EQ(d->render_vertex_count(), r.source.size());
    EXPECT_EQ(std::vector<uint32_t>(d->render_source(), d->render_source() + r.source.size()), r.source);
    EXPECT_EQ(std::vector<uint32_t>(d->render_faces(), d->render_faces() + r.corners.size()), r.corners);
    for (const RenderAttribute& a : r.attributes) {
      const Attribute which = Attribute(int(a.semantic));
      ASSERT_EQ(d->attribute_components(which), a.components);
      for (size_t i = 0; i < a.q.size(); ++i)
        EXPECT_EQ(d->attribute(which)[i], a.value(i / a.components, uint32_t(i % a.components))) << v.name << " " << i;
    }
    double matrix[16];
    EXPECT_EQ(d->world_matrix(matrix), v.model.placement.has_matrix);
    EXPECT_EQ(std::vector<double>(matrix, matrix + 16), std::vector<double>(v.model.placement.matrix, v.model.placement.matrix + 16));
    EXPECT_EQ(d->start_time(), v.model.placement.start_time);
    EXPECT_EQ(d->mesh_name(), v.model.placement.mesh_name);
    EXPECT_EQ(d->node_name(), v.model.placement.node_name);
    // Groups: triangles 0 and 2, then 1 and 3, each group's in the faces' order.
    ASSERT_EQ(d->group_count(), r.groups.size());
    const std::vector<uint32_t> grouped(d->group_faces(), d->group_faces() + r.corners.size());
    EXPECT_EQ(grouped, (std::vector<uint32_t>{0, 1, 2, 6, 7, 4, 2, 1, 3, 4, 5, 6}));
    EXPECT_EQ(d->group(1).first_face, 2u);
    EXPECT_EQ(d->group(1).face_count, 2u);
    EXPECT_EQ(d->group(1).material, 0);
    EXPECT_EQ(d->group_name(1), "cloth");
    EXPECT_EQ(d->group(0).material, -1);
    EXPECT_EQ(d->materials_json(), v.model.materials.json);
    ASSERT_EQ(d->image_count(), 1u);
    size_t size = 0;
    const uint8_t* image = d->image(0, &size);
    EXPECT_EQ(std::vector<uint8_t>(image, image + size), v.model.materials.images[0].bytes);
    EXPECT_EQ(d->image_mime_type(0), "image/png");
  }
}

TEST(TestVectors, Format30FilesStillDecode) { expect_older_files_decode("3.0", 0); }
TEST(TestVectors, Format31FilesStillDecode) { expect_older_files_decode("3.1", 1); }

}  // namespace
}  // namespace dcurve
