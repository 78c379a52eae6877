// TetGen tetrahedralization of the procedural surfaces and of bad input.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>

#include "corpus/surfaces.h"
#include "encoder/io/frames.h"
#include "corpus/sim/tetrahedralize.h"

namespace dcurve {
namespace {

double surface_volume(const corpus::SurfaceMesh& m) {
  double v = 0;
  for (size_t i = 0; i < m.faces.size(); i += 3) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = Eigen::Map<const Eigen::Vector3d>(&m.xyz[3 * size_t(m.faces[i + k])]);
    v += p[0].dot(p[1].cross(p[2])) / 6;
  }
  return v;
}

double tet_volume(const TetMesh& t) {
  double v = 0;
  for (const auto& tet : t.tets) {
    const Eigen::Vector3d& a = t.points[tet[0]];
    const double one = (t.points[tet[1]] - a).cross(t.points[tet[2]] - a).dot(t.points[tet[3]] - a) / 6;
    EXPECT_GT(one, 0);
    v += one;
  }
  return v;
}

TEST(SimTetra, GeneratedSurfacesAreClosedOutwardAndHaveTheRightVolume) {
  const double pi = std::acos(-1.0);
  struct Case {
    corpus::SurfaceMesh mesh;
    double volume, tolerance;
  } cases[] = {
      {corpus::box_surface(0.5, 0.1, 0.2, 10, 2, 4), 0.5 * 0.1 * 0.2, 1e-12},
      {corpus::sphere_surface(0.3, 8), 4.0 / 3 * pi * 0.027, 0.03},
      {corpus::tube_surface(0.03, 0.05, 0.4, 32, 6), pi * (0.05 * 0.05 - 0.03 * 0.03) * 0.4, 0.02},
  };
  for (const auto& c : cases) {
    std::string err;
    EXPECT_TRUE(check_closed_surface(c.mesh.xyz, c.mesh.faces, &err)) << err;
    EXPECT_NEAR(surface_volume(c.mesh), c.volume, c.tolerance * c.volume);
  }
  EXPECT_EQ(corpus::box_surface(1, 1, 1, 3, 4, 5).xyz.size() / 3, size_t(2 * (12 + 20 + 15) + 2));
}

TEST(SimTetra, KeepsTheSurfaceVerticesAndFillsTheVolume) {
  for (const auto& m : {corpus::box_surface(0.5, 0.1, 0.2, 10, 2, 4), corpus::tube_surface(0.03, 0.05, 0.4, 16, 8)}) {
    TetMesh t;
    std::string err;
    ASSERT_TRUE(tetrahedralize_surface(m.xyz, m.faces, TetOptions{2.0, 1e-4}, &t, &err)) << err;
    ASSERT_EQ(t.surface_vertex_count, m.xyz.size() / 3);
    ASSERT_GE(t.points.size(), t.surface_vertex_count);
    for (uint32_t i = 0; i < t.surface_vertex_count; ++i)
      EXPECT_EQ(t.points[i], Eigen::Map<const Eigen::Vector3d>(&m.xyz[3 * size_t(i)])) << i;
    EXPECT_NEAR(tet_volume(t), surface_volume(m), 1e-9 * surface_volume(m));
  }
}

TEST(SimTetra, MaxVolumeRefines) {
  const auto m = corpus::box_surface(0.4, 0.1, 0.1, 8, 2, 2);
  TetMesh coarse, fine;
  std::string err;
  ASSERT_TRUE(tetrahedralize_surface(m.xyz, m.faces, TetOptions{0, 0}, &coarse, &err)) << err;
  ASSERT_TRUE(tetrahedralize_surface(m.xyz, m.faces, TetOptions{2.0, 2e-5}, &fine, &err)) << err;
  EXPECT_GT(fine.tets.size(), coarse.tets.size());
  // -Y keeps the boundary, so the refinement shows as interior (Steiner) points.
  EXPECT_GT(fine.points.size(), fine.surface_vertex_count);
  EXPECT_NEAR(tet_volume(fine), tet_volume(coarse), 1e-12);
}

TEST(SimTetra, BadSurfacesGetAClearError) {
  const auto box = corpus::box_surface(1, 1, 1, 2, 2, 2);
  TetMesh t;
  std::string err;
  auto open = box;
  open.faces.resize(open.faces.size() - 6);
  EXPECT_FALSE(tetrahedralize_surface(open.xyz, open.faces, {}, &t, &err));
  EXPECT_NE(err.find("not closed"), std::string::npos) << err;

  auto flat = box;
  flat.faces[2] = flat.faces[1];  // a triangle with a repeated corner
  EXPECT_FALSE(tetrahedralize_surface(flat.xyz, flat.faces, {}, &t, &err));
  EXPECT_NE(err.find("degenerate"), std::string::npos) << err;

  auto flipped = box;
  std::swap(flipped.faces[0], flipped.faces[1]);
  EXPECT_FALSE(tetrahedralize_surface(flipped.xyz, flipped.faces, {}, &t, &err));
  EXPECT_NE(err.find("oriented"), std::string::npos) << err;

  auto nan = box;
  nan.xyz[4] = std::nan("");
  EXPECT_FALSE(tetrahedralize_surface(nan.xyz, nan.faces, {}, &t, &err));
  EXPECT_NE(err.find("non-finite"), std::string::npos) << err;

  auto stray = box;
  stray.xyz.insert(stray.xyz.end(), {0.0, 0.0, 0.0});
  EXPECT_FALSE(tetrahedralize_surface(stray.xyz, stray.faces, {}, &t, &err));
  EXPECT_NE(err.find("not used"), std::string::npos) << err;

  // Two interpenetrating closed boxes: each is fine alone, together they self-intersect.
  auto twice = box;
  const auto moved = corpus::box_surface(1, 1, 1, 2, 2, 2);
  const uint32_t offset = uint32_t(twice.xyz.size() / 3);
  for (size_t i = 0; i < moved.xyz.size(); ++i) twice.xyz.push_back(moved.xyz[i] + (i % 3 == 0 ? 0.3 : 0.2));
  for (uint32_t v : moved.faces) twice.faces.push_back(v + offset);
  EXPECT_FALSE(tetrahedralize_surface(twice.xyz, twice.faces, {}, &t, &err));
  EXPECT_FALSE(err.empty());
  std::printf("self-intersection: %s\n", err.c_str());
}

TEST(SimTetra, RealScanFromTheExternalCorpus) {
  const std::string path = std::string(DCURVE_CORPUS_EXT) + "/static/bunny.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is absent";
  std::vector<float> xyzf;
  std::vector<uint32_t> faces;
  std::string err;
  ASSERT_TRUE(read_mesh(path, &xyzf, &faces, &err)) << err;
  const std::vector<double> xyz(xyzf.begin(), xyzf.end());
  TetMesh t;
  ASSERT_TRUE(tetrahedralize_surface(xyz, faces, TetOptions{}, &t, &err)) << err;
  EXPECT_EQ(t.surface_vertex_count, xyz.size() / 3);
  EXPECT_GT(tet_volume(t), 0);
}

}  // namespace
}  // namespace dcurve
