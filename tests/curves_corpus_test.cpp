// Curve extraction on every mesh of corpus-ext (static meshes and frame 0 of each sequence):
// the partition invariant, u endpoints, and quality bars; prints the per-mesh report table
// (run ./build/tests/dcurve_tests --gtest_filter='CurvesCorpus.*' to see it). Skips when the
// corpus is absent.
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

// u = 0 at each curve's start and 1 at an open curve's end (check_partition checks the rest).
void expect_u_endpoints(const Curves& curves, const std::string& path) {
  for (uint32_t c = 0; c < curves.curve_count(); ++c) {
    const uint32_t b = curves.offsets[c], n = curves.offsets[c + 1] - b;
    EXPECT_EQ(curves.u[b], 0.f) << path << " curve " << c;
    if (n >= 2 && !curves.closed[c]) {
      EXPECT_EQ(curves.u[b + n - 1], 1.f) << path << " curve " << c;
    }
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

// Each mesh is read and extracted once (the test also runs under sanitizers): partition and u
// checks, quality bars, then the naive baseline and the coordinate-range rule on the same curves.
TEST(CurvesCorpus, EveryMeshPartitionsIntoGoodCurves) {
  const std::vector<std::string> meshes = corpus_meshes();
  if (meshes.empty()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  std::string table = "| mesh | vertices | target | curves | closed | mean pts | median pts | short frac | mean turn deg | wall ms | cpu ms |\n"
                      "|---|---|---|---|---|---|---|---|---|---|---|\n";
  std::string compare = "| mesh | curves | naive curves | mean turn deg | naive mean turn deg | coord-range: mean abs u diff | coord-range: zero steps |\n"
                        "|---|---|---|---|---|---|---|\n";
  char row[256];
  for (const std::string& path : meshes) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string error;
    ASSERT_TRUE(read_mesh(path, &xyz, &faces, &error)) << error;
    const uint32_t V = uint32_t(xyz.size() / 3);
    const CurveOptions options;
    Curves curves;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    ASSERT_TRUE(extract_curves(xyz, V, faces, options, &curves, &error)) << path << ": " << error;
    const double cpu_ms = 1000.0 * double(std::clock() - c0) / CLOCKS_PER_SEC;
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(check_partition(curves, V, faces, &error)) << path << ": " << error;
    expect_u_endpoints(curves, path);
    // corpus-ext has no duplicate vertices, so chord-length u strictly increases.
    for (uint32_t c = 0; c < curves.curve_count(); ++c)
      for (uint32_t i = curves.offsets[c] + 1; i < curves.offsets[c + 1]; ++i)
        ASSERT_GT(curves.u[i], curves.u[i - 1]) << path << " curve " << c;
    const CurveReport r = curve_report(curves, xyz);
    uint32_t closed = 0;
    for (uint8_t f : curves.closed) closed += f;
    std::snprintf(row, sizeof row, "| %-32s | %6u | %2u | %6u | %5u | %6.1f | %6.1f | %6.4f | %6.1f | %6.1f | %6.1f |\n",
                  short_name(path).c_str(), V, options.target_points, r.curves, closed, r.mean_points_per_curve,
                  r.median_points_per_curve, r.short_curve_vertex_fraction, r.mean_turning_angle_deg, ms, cpu_ms);
    table += row;
    // Quality bars from the issue: few very short curves, runs far longer than a few points, and
    // no random walks (linking edges in file order, the baseline below, turns by 54 to 75
    // degrees on average on the irregular meshes here).
    EXPECT_LT(r.short_curve_vertex_fraction, 0.03) << path;
    EXPECT_GT(r.mean_points_per_curve, 12.0) << path;
    EXPECT_LT(r.mean_turning_angle_deg, 50.0) << path;

    Curves coord = curves;
    for (uint32_t c = 0; c < coord.curve_count(); ++c) parameterize_curve(&coord, c, xyz, ParamRule::CoordinateRange);
    ASSERT_TRUE(check_partition(coord, V, faces, &error)) << path << ": " << error;
    expect_u_endpoints(coord, path);
    double u_diff = 0.0;
    size_t zero_steps = 0, steps = 0;
    for (uint32_t c = 0; c < coord.curve_count(); ++c)
      for (uint32_t i = coord.offsets[c]; i < coord.offsets[c + 1]; ++i) {
        u_diff += std::fabs(double(coord.u[i]) - curves.u[i]);
        if (i > coord.offsets[c]) {
          ++steps;
          zero_steps += coord.u[i] == coord.u[i - 1];
        }
      }
    Curves naive = naive_curves(xyz, V, faces);
    naive.u.assign(V, 0.f);  // cut_to_target leaves u to the caller
    ASSERT_TRUE(check_partition(naive, V, faces, &error)) << error;
    const CurveReport base = curve_report(naive, xyz);
    std::snprintf(row, sizeof row, "| %-32s | %6u | %6u | %5.1f | %5.1f | %6.4f | %6.4f |\n", short_name(path).c_str(),
                  r.curves, base.curves, r.mean_turning_angle_deg, base.mean_turning_angle_deg, u_diff / V,
                  steps ? double(zero_steps) / steps : 0.0);
    compare += row;
    // Following a field must give straighter curves than linking edges in file order.
    EXPECT_LT(r.mean_turning_angle_deg, base.mean_turning_angle_deg) << path;
  }
  std::printf("%s\n%s", table.c_str(), compare.c_str());
}

// bend_weight trades curve count for straightness on real meshes, as it does on a grid.
TEST(CurvesCorpus, BendWeightSweep) {
  const fs::path root(DCURVE_CORPUS_EXT);
  const std::vector<std::string> meshes = {(root / "horse-gallop" / "frame_00000.obj").string(),
                                           (root / "crane" / "frame_00000.obj").string()};
  std::error_code ec;
  if (!fs::exists(meshes[0], ec) || !fs::exists(meshes[1], ec)) GTEST_SKIP() << "corpus-ext not found";
  std::printf("| mesh | bend_weight | curves | mean pts | short frac | mean turn deg |\n|---|---|---|---|---|---|\n");
  for (const std::string& path : meshes) {
    std::vector<float> xyz;
    std::vector<uint32_t> faces;
    std::string error;
    ASSERT_TRUE(read_mesh(path, &xyz, &faces, &error)) << error;
    std::vector<CurveReport> reports;
    for (double w : {0.0, 0.3, 1.0}) {
      CurveOptions options;
      options.bend_weight = w;
      Curves curves;
      ASSERT_TRUE(extract_curves(xyz, uint32_t(xyz.size() / 3), faces, options, &curves, &error)) << error;
      reports.push_back(curve_report(curves, xyz));
      const CurveReport& r = reports.back();
      std::printf("| %s | %.1f | %u | %.1f | %.4f | %.1f |\n", short_name(path).c_str(), w, r.curves,
                  r.mean_points_per_curve, r.short_curve_vertex_fraction, r.mean_turning_angle_deg);
    }
    EXPECT_LT(reports[0].curves, reports[2].curves) << path;
    EXPECT_GT(reports[0].mean_turning_angle_deg, reports[2].mean_turning_angle_deg) << path;
  }
}

}  // namespace
}  // namespace dcurve
