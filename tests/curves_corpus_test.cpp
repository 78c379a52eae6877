// Curve extraction on every mesh of corpus-ext (static meshes and frame 0 of each sequence):
// the partition invariant, u endpoints, and quality bars; prints the per-mesh report table
// (run ./build/tests/curves_corpus_test to see it). Skips when the corpus is absent.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>

#include "encoder/curves/extract.h"
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
  ASSERT_TRUE(extract_curves(xyz, V, faces, options, &curves, &error)) << path << ": " << error;
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
    std::printf("| %-31s | %6u | %2u | %6u | %5u | %6.1f | %6.1f | %6.4f | %6.1f | %7.1f |\n", short_name(path).c_str(), V,
                options.target_points, r.curves, closed, r.mean_points_per_curve, r.median_points_per_curve,
                r.short_curve_vertex_fraction, r.mean_turning_angle_deg, ms);
  // Quality bars from the issue: few very short curves, runs far longer than a few points, and
  // no random walks (a walk choosing random neighbours turns by about 80-90 degrees on average).
  EXPECT_LT(r.short_curve_vertex_fraction, 0.03) << path;
  EXPECT_GT(r.mean_points_per_curve, 12.0) << path;
  EXPECT_LT(r.mean_turning_angle_deg, 50.0) << path;
}

TEST(CurvesCorpus, EveryMeshPartitionsIntoGoodCurves) {
  const std::vector<std::string> meshes = corpus_meshes();
  if (meshes.empty()) GTEST_SKIP() << "corpus-ext not found at " << DCURVE_CORPUS_EXT;
  std::printf("| mesh | vertices | target | curves | closed | mean pts | median pts | short frac | mean turn deg | ms |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|\n");
  for (uint32_t target : {64u, 32u}) {
    CurveOptions options;
    options.target_points = target;
    for (const std::string& path : meshes) check_mesh(path, options, true);
  }
}

}  // namespace
}  // namespace dcurve
