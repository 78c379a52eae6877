// Curve extraction on every mesh of corpus-ext (static meshes and frame 0 of each sequence):
// the partition invariant, u endpoints, and quality bars; prints the per-mesh report table
// (run ./build/tests/curves_corpus_test to see it). Skips when the corpus is absent.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <ctime>
#include <filesystem>

#include "encoder/curves/cut_to_target.h"
#include "encoder/curves/extract.h"
#include "encoder/curves/link_paths.h"
#include "encoder/curves/report.h"
#include "encoder/io/frames.h"

namespace dcurve {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> corpus_meshes() {
  std::vector<std::string> out;
  const fs::path root(DCURVE_CORPUS_EXT);
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return out;
  for (const auto& e : fs::directory_iterator(root)) {
    if (!e.is_directory()) continue;
    if (e.path().filename() == "static") {
      for (const auto& s : fs::directory_iterator(e.path()))
        if (s.path().extension() == ".obj") out.push_back(s.path().string());
    } else if (fs::exists(e.path() / "frame_00000.obj")) {
      out.push_back((e.path() / "frame_00000.obj").string());
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string short_name(const std::string& path) {
  const fs::path p(path);
  return p.parent_path().filename().string() + "/" + p.filename().string();
}

void check_mesh(const std::string& path, const CurveOptions& options, bool print) {
  std::vector<float> xyz;
  std::vector<uint32_t> faces;
  std::string error;
  ASSERT_TRUE(read_mesh(path, &xyz, &faces, &error)) << error;
  const uint32_t V = uint32_t(xyz.size() / 3);
  Curves curves;
  const auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  ASSERT_TRUE(extract_curves(xyz, V, faces, options, &curves, &error)) << path << ": " << error;
  const double cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(check_partition(curves, V, faces, &error)) << path << ": " << error;
  for (uint32_t c = 0; c < curves.curve_count(); ++c) {
    const uint32_t b = curves.offsets[c], n = curves.offsets[c + 1] - b;
    ASSERT_EQ(curves.u[b], 0.f) << path << " curve " << c;
    if (n >= 2 && !curves.closed[c]) {
      ASSERT_EQ(curves.u[b + n - 1], 1.f) << path << " curve " << c;
    }
    for (uint32_t i = b + 1; i < b + n; ++i)
      ASSERT_GE(curves.u[i], curves.u[i - 1]) << path << " curve " << c;
  }
  const CurveReport r = curve_report(curves, xyz);
  uint32_t closed = 0;
  for (uint8_t f : curves.closed) closed += f;
  if (print)
    std::printf("| %-32s | %6u | %2u | %6u | %5u | %6.1f | %6.1f | %6.4f | %6.1f | %6.1f | %6.1f |\n",
                short_name(path).c_str(), V, options.target_points, r.curves, closed, r.mean_points_per_curve,
                r.median_points_per_curve, r.short_curve_vertex_fraction, r.mean_turning_angle_deg, ms, cpu_ms);
  // Quality bars from the issue: few very short curves, runs far longer than a few points, and
  // no random walks (a walk choosing random neighbours turns by about 80-90 degrees on average).
  EXPECT_LT(r.short_curve_vertex_fraction, 0.03) << path;
  EXPECT_GT(r.mean_points_per_curve, 12.0) << path;
  EXPECT_LT(r.mean_turning_angle_deg, 50.0) << path;
}

TEST(CurvesCorpus, EveryMeshPartitionsIntoGoodCurves) {
  const std::vector<std::string> meshes = corpus_meshes();
  if (meshes.empty()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  std::printf("| mesh | vertices | target | curves | closed | mean pts | median pts | short frac | mean turn deg | wall ms | cpu ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (uint32_t target : {64u, 32u}) {
    CurveOptions options;
    options.target_points = target;
    for (const std::string& path : meshes) check_mesh(path, options, true);
  }
}

// The same linking and cutting without a direction field, straightness passes or joins: edges
// taken in index order, any turn allowed. What extraction must beat.
Curves naive_curves(const std::vector<float>& xyz, uint32_t V, const std::vector<uint32_t>& faces) {
  curves_detail::SurfaceGraph graph;
  std::string error;
  EXPECT_TRUE(curves_detail::build_surface_graph(xyz, V, faces, &graph, &error)) << error;
  curves_detail::LinkParams params;
  params.passes = {{180.0, 0, false}};
  params.join_sweeps = 0;
  const std::vector<float> no_field(size_t(V) * 3, 0.f);
  Curves runs;
  curves_detail::assemble_paths(curves_detail::link_along_field(graph, xyz, no_field, params), &runs);
  return curves_detail::cut_to_target(runs, xyz, CurveOptions{}.target_points, CurveOptions{}.bend_weight);
}

TEST(CurvesCorpus, BeatsNaiveLinkingAndComparesURules) {
  const std::vector<std::string> meshes = corpus_meshes();
  if (meshes.empty()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  std::printf("| mesh | curves | naive curves | mean turn deg | naive mean turn deg | coord-range: mean abs u diff | coord-range: zero steps |\n");
  std::printf("|---|---|---|---|---|---|---|\n");
  for (const std::string& path : meshes) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string error;
    ASSERT_TRUE(read_mesh(path, &xyz, &faces, &error)) << error;
    const uint32_t V = uint32_t(xyz.size() / 3);
    Curves chord, coord;
    CurveOptions options;
    ASSERT_TRUE(extract_curves(xyz, V, faces, options, &chord, &error)) << error;
    options.u_rule = ParamRule::CoordinateRange;
    ASSERT_TRUE(extract_curves(xyz, V, faces, options, &coord, &error)) << error;
    ASSERT_TRUE(check_partition(coord, V, faces, &error)) << path << ": " << error;
    ASSERT_EQ(chord.vertices, coord.vertices);  // the rule changes u only
    double u_diff = 0.0;
    size_t zero_steps = 0, steps = 0;
    for (uint32_t c = 0; c < coord.curve_count(); ++c)
      for (uint32_t i = coord.offsets[c]; i < coord.offsets[c + 1]; ++i) {
        u_diff += std::fabs(double(coord.u[i]) - chord.u[i]);
        if (i > coord.offsets[c]) {
          ++steps;
          zero_steps += coord.u[i] == coord.u[i - 1];
        }
      }
    const Curves naive = naive_curves(xyz, V, faces);
    ASSERT_TRUE(naive.vertices.size() == V);
    const CurveReport ours = curve_report(chord, xyz), base = curve_report(naive, xyz);
    std::printf("| %-32s | %6u | %6u | %5.1f | %5.1f | %6.4f | %6.4f |\n", short_name(path).c_str(), ours.curves,
                base.curves, ours.mean_turning_angle_deg, base.mean_turning_angle_deg, u_diff / V,
                steps ? double(zero_steps) / steps : 0.0);
    // Following a field must give straighter curves than linking edges in file order.
    EXPECT_LT(ours.mean_turning_angle_deg, base.mean_turning_angle_deg) << path;
  }
}

}  // namespace
}  // namespace dcurve
