#include "corpus/sim/tetrahedralize.h"

#include <tetgen.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace dcurve {
namespace {

Eigen::Vector3d vertex(const std::vector<double>& xyz, uint32_t i) {
  return Eigen::Vector3d(xyz[3 * size_t(i)], xyz[3 * size_t(i) + 1], xyz[3 * size_t(i) + 2]);
}

const char* tetgen_error_text(int code) {
  switch (code) {
    case 1: return "out of memory";
    case 3: return "the surface intersects itself";
    case 4: return "a very small input feature (nearly touching parts of the surface)";
    case 5: return "two surface segments intersect";
    case 10: return "a triangle overlaps another one";
    default: return "TetGen internal error";
  }
}

}  // namespace

bool check_closed_surface(const std::vector<double>& xyz, const std::vector<uint32_t>& faces, std::string* error) {
  const size_t nv = xyz.size() / 3, nf = faces.size() / 3;
  if (xyz.size() % 3 || faces.size() % 3 || nv < 4 || nf < 4) {
    *error = "surface needs at least 4 vertices and 4 triangles";
    return false;
  }
  for (double c : xyz)
    if (!std::isfinite(c)) {
      *error = "surface has a non-finite coordinate";
      return false;
    }
  Eigen::Vector3d lo = vertex(xyz, 0), hi = lo;
  for (size_t i = 1; i < nv; ++i) {
    lo = lo.cwiseMin(vertex(xyz, uint32_t(i)));
    hi = hi.cwiseMax(vertex(xyz, uint32_t(i)));
  }
  const double diag = (hi - lo).norm();
  std::vector<std::pair<uint64_t, uint32_t>> directed;  // (from << 32 | to, face) per edge
  directed.reserve(faces.size());
  std::vector<char> used(nv, 0);
  for (size_t f = 0; f < nf; ++f) {
    const uint32_t* t = &faces[3 * f];
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) {
      *error = "triangle " + std::to_string(f) + " has a vertex index out of range";
      return false;
    }
    const double area2 = (vertex(xyz, t[1]) - vertex(xyz, t[0])).cross(vertex(xyz, t[2]) - vertex(xyz, t[0])).norm();
    if (!(area2 > 1e-12 * diag * diag)) {
      *error = "triangle " + std::to_string(f) + " is degenerate (zero area)";
      return false;
    }
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = 1;
      directed.emplace_back(uint64_t(t[k]) << 32 | t[(k + 1) % 3], uint32_t(f));
    }
  }
  for (size_t i = 0; i < nv; ++i)
    if (!used[i]) {
      *error = "vertex " + std::to_string(i) + " is not used by any triangle";
      return false;
    }
  std::sort(directed.begin(), directed.end());
  for (size_t i = 0; i < directed.size(); ++i) {
    const uint64_t e = directed[i].first;
    const uint32_t a = uint32_t(e >> 32), b = uint32_t(e);
    if (i + 1 < directed.size() && directed[i + 1].first == e) {
      *error = "edge " + std::to_string(a) + "-" + std::to_string(b) +
               " is used more than once in the same direction (non-manifold or inconsistently oriented)";
      return false;
    }
    const uint64_t twin = uint64_t(b) << 32 | a;
    if (!std::binary_search(directed.begin(), directed.end(), std::make_pair(twin, uint32_t(0)),
                            [](const auto& x, const auto& y) { return x.first < y.first; })) {
      *error = "surface is not closed: edge " + std::to_string(a) + "-" + std::to_string(b) + " of triangle " +
               std::to_string(directed[i].second) + " has no neighbour";
      return false;
    }
  }
  return true;
}

bool tetrahedralize_surface(const std::vector<double>& xyz, const std::vector<uint32_t>& faces,
                            const TetOptions& options, TetMesh* out, std::string* error) {
  if (!check_closed_surface(xyz, faces, error)) return false;
  const int nv = int(xyz.size() / 3), nf = int(faces.size() / 3);
  tetgenio in, result;
  in.firstnumber = 0;
  in.numberofpoints = nv;
  in.pointlist = new REAL[xyz.size()];
  std::copy(xyz.begin(), xyz.end(), in.pointlist);
  in.numberoffacets = nf;
  in.facetlist = new tetgenio::facet[nf];
  for (int f = 0; f < nf; ++f) {
    tetgenio::facet& fc = in.facetlist[f];
    tetgenio::init(&fc);
    fc.numberofpolygons = 1;
    fc.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fc.polygonlist[0]);
    fc.polygonlist[0].numberofvertices = 3;
    fc.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) fc.polygonlist[0].vertexlist[k] = int(faces[3 * f + k]);
  }
  // TetGen 1.5 frees its memory twice when it stops on a self-intersection (a crash), so
  // look for intersections first with its detector (-d), which reports them as faces.
  {
    tetgenio found;
    char detect[] = "pdQz";
    try {
      tetrahedralize(detect, &in, &found);
    } catch (...) {
      *error = "TetGen could not check the surface for self-intersections";
      return false;
    }
    if (found.numberoftrifaces > 0) {
      *error = "the surface intersects itself (" + std::to_string(found.numberoftrifaces) +
               " triangles involved, first near vertex " + std::to_string(found.trifacelist[0]) + ")";
      return false;
    }
  }
  // p: piecewise linear complex, Y: keep the boundary, Q: quiet, z: zero-based ids.
  char switches[128];
  int len = std::snprintf(switches, sizeof switches, "pYQz");
  if (options.quality > 0) len += std::snprintf(switches + len, sizeof switches - len, "q%.6g", options.quality);
  if (options.max_volume > 0) std::snprintf(switches + len, sizeof switches - len, "a%.9g", options.max_volume);
  try {
    tetrahedralize(switches, &in, &result);
  } catch (int code) {
    *error = std::string("TetGen failed: ") + tetgen_error_text(code);
    return false;
  } catch (...) {
    *error = "TetGen failed";
    return false;
  }
  if (result.numberofpoints < nv || result.numberoftetrahedra < 1 || result.numberofcorners != 4) {
    *error = "TetGen produced no usable tet mesh";
    return false;
  }
  TetMesh m;
  m.surface_vertex_count = uint32_t(nv);
  m.points.resize(size_t(result.numberofpoints));
  for (int i = 0; i < result.numberofpoints; ++i)
    m.points[i] = Eigen::Vector3d(result.pointlist[3 * i], result.pointlist[3 * i + 1], result.pointlist[3 * i + 2]);
  for (int i = 0; i < nv; ++i)
    if (m.points[i] != vertex(xyz, uint32_t(i))) {
      *error = "TetGen moved or merged surface vertex " + std::to_string(i) + " (duplicate vertices?)";
      return false;
    }
  std::vector<char> in_tet(size_t(result.numberofpoints), 0);
  m.tets.resize(size_t(result.numberoftetrahedra));
  for (int t = 0; t < result.numberoftetrahedra; ++t) {
    Eigen::Vector4i& tet = m.tets[t];
    for (int k = 0; k < 4; ++k) {
      tet[k] = result.tetrahedronlist[4 * t + k];
      if (tet[k] < 0 || tet[k] >= result.numberofpoints) {
        *error = "TetGen produced an invalid tet";
        return false;
      }
      in_tet[tet[k]] = 1;
    }
    const Eigen::Vector3d &a = m.points[tet[0]], &b = m.points[tet[1]], &c = m.points[tet[2]], &d = m.points[tet[3]];
    if ((b - a).cross(c - a).dot(d - a) < 0) std::swap(tet[2], tet[3]);
  }
  for (int i = 0; i < nv; ++i)
    if (!in_tet[i]) {
      *error = "surface vertex " + std::to_string(i) + " ended up in no tet";
      return false;
    }
  *out = std::move(m);
  return true;
}

}  // namespace dcurve
