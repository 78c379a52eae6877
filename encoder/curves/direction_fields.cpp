#include "encoder/curves/direction_fields.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>

namespace dcurve {
namespace curves_detail {
namespace {

using Vec3 = Eigen::Vector3d;

Vec3 point(const std::vector<float>& xyz, uint32_t v) {
  return Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
}
Vec3 normal(const SurfaceGraph& g, uint32_t v) {
  return Vec3(g.normals[3 * v], g.normals[3 * v + 1], g.normals[3 * v + 2]);
}

// Principal axes (columns, largest variance first) of each component's vertices.
std::vector<Eigen::Matrix3d> component_axes(const SurfaceGraph& g, const std::vector<float>& xyz) {
  const uint32_t C = g.component_count;
  std::vector<Vec3> sum(C, Vec3::Zero());
  std::vector<Eigen::Matrix3d> outer(C, Eigen::Matrix3d::Zero());
  std::vector<double> count(C, 0.0);
  for (uint32_t v = 0; v < g.vertex_count; ++v) {
    const uint32_t c = g.component[v];
    const Vec3 p = point(xyz, v);
    sum[c] += p;
    outer[c] += p * p.transpose();
    count[c] += 1.0;
  }
  std::vector<Eigen::Matrix3d> axes(C);
  for (uint32_t c = 0; c < C; ++c) {
    const Vec3 mean = sum[c] / count[c];
    const Eigen::Matrix3d cov = outer[c] / count[c] - mean * mean.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
    // Eigen sorts eigenvalues ascending; reverse so column 0 is the longest axis.
    for (int k = 0; k < 3; ++k) axes[c].col(k) = solver.eigenvectors().col(2 - k);
  }
  return axes;
}

void store(std::vector<float>* dir, uint32_t v, const Vec3& d) {
  for (int a = 0; a < 3; ++a) (*dir)[3 * v + a] = float(d[a]);
}

// Fields of the height function h(p) = p . axis: its surface gradient is the axis projected
// on the tangent plane, its iso-lines run along n x axis. Both shrink where the surface faces
// the axis, which is exactly where the direction is ill-defined.
void height_fields(const SurfaceGraph& g, const std::vector<Eigen::Matrix3d>& axes,
                   const std::function<Vec3(const Eigen::Matrix3d&)>& pick, const std::string& name,
                   std::vector<DirectionField>* out) {
  DirectionField along{name + "-along", std::vector<float>(size_t(g.vertex_count) * 3, 0.f)};
  DirectionField across{name + "-across", std::vector<float>(size_t(g.vertex_count) * 3, 0.f)};
  for (uint32_t v = 0; v < g.vertex_count; ++v) {
    const Vec3 n = normal(g, v);
    if (n.squaredNorm() == 0.0) continue;
    const Vec3 axis = pick(axes[g.component[v]]);
    store(&along.dir, v, axis - axis.dot(n) * n);
    store(&across.dir, v, n.cross(axis));
  }
  out->push_back(std::move(along));
  out->push_back(std::move(across));
}

// Edge-length Dijkstra distance from `sources` (one per component). Iso-lines of a distance
// from an extremity wrap around limbs; its gradient runs down them.
std::vector<double> geodesic_distance(const SurfaceGraph& g, const std::vector<float>& xyz,
                                      const std::vector<uint32_t>& sources) {
  std::vector<double> dist(g.vertex_count, HUGE_VAL);
  using Item = std::pair<double, uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  for (uint32_t s : sources) {
    dist[s] = 0.0;
    heap.push({0.0, s});
  }
  while (!heap.empty()) {
    const auto [d, v] = heap.top();
    heap.pop();
    if (d > dist[v]) continue;
    const Vec3 pv = point(xyz, v);
    for (uint32_t k = g.adj_offsets[v]; k < g.adj_offsets[v + 1]; ++k) {
      const uint32_t w = g.adj[k];
      const double nd = d + (point(xyz, w) - pv).norm();
      if (nd < dist[w]) {
        dist[w] = nd;
        heap.push({nd, w});
      }
    }
  }
  return dist;
}

// Piecewise-linear gradient of a vertex scalar, area-weighted over the faces around each vertex.
std::vector<Vec3> vertex_gradients(const SurfaceGraph& g, const std::vector<float>& xyz,
                                   const std::vector<uint32_t>& faces, const std::vector<double>& f) {
  std::vector<Vec3> grad(g.vertex_count, Vec3::Zero());
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    const uint32_t i[3] = {faces[t], faces[t + 1], faces[t + 2]};
    const Vec3 p[3] = {point(xyz, i[0]), point(xyz, i[1]), point(xyz, i[2])};
    const Vec3 cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const double twice_area = cross.norm();
    if (!(twice_area > 0.0)) continue;
    const Vec3 n = cross / twice_area;
    // area * gradient = 1/2 sum_k f_k (n x e_k), e_k the edge opposite corner k.
    const Vec3 ag = 0.5 * (f[i[0]] * n.cross(p[2] - p[1]) + f[i[1]] * n.cross(p[0] - p[2]) +
                           f[i[2]] * n.cross(p[1] - p[0]));
    for (uint32_t v : i) grad[v] += ag;
  }
  return grad;
}

void scalar_fields(const SurfaceGraph& g, const std::vector<Vec3>& grad, const std::string& name,
                   std::vector<DirectionField>* out) {
  DirectionField along{name + "-along", std::vector<float>(size_t(g.vertex_count) * 3, 0.f)};
  DirectionField across{name + "-across", std::vector<float>(size_t(g.vertex_count) * 3, 0.f)};
  for (uint32_t v = 0; v < g.vertex_count; ++v) {
    const Vec3 n = normal(g, v);
    Vec3 d = grad[v] - grad[v].dot(n) * n;
    const double len = d.norm();
    if (!(len > 0.0)) continue;
    d /= len;
    store(&along.dir, v, d);
    store(&across.dir, v, n.cross(d));
  }
  out->push_back(std::move(along));
  out->push_back(std::move(across));
}

}  // namespace

std::vector<DirectionField> candidate_fields(const SurfaceGraph& g, const std::vector<float>& xyz,
                                             const std::vector<uint32_t>& faces) {
  const std::vector<Eigen::Matrix3d> axes = component_axes(g, xyz);
  std::vector<DirectionField> out;
  const double h = std::sqrt(0.5);
  height_fields(g, axes, [](const Eigen::Matrix3d& a) -> Vec3 { return a.col(0); }, "axis0", &out);
  height_fields(g, axes, [](const Eigen::Matrix3d& a) -> Vec3 { return a.col(1); }, "axis1", &out);
  height_fields(g, axes, [](const Eigen::Matrix3d& a) -> Vec3 { return a.col(2); }, "axis2", &out);
  height_fields(g, axes, [h](const Eigen::Matrix3d& a) -> Vec3 { return h * (a.col(0) + a.col(1)); },
                "diag01+", &out);
  height_fields(g, axes, [h](const Eigen::Matrix3d& a) -> Vec3 { return h * (a.col(0) - a.col(1)); },
                "diag01-", &out);

  // Source per component: the vertex lowest along its first axis (smallest id on ties).
  std::vector<uint32_t> source(g.component_count, UINT32_MAX);
  std::vector<double> lowest(g.component_count, HUGE_VAL);
  for (uint32_t v = 0; v < g.vertex_count; ++v) {
    const uint32_t c = g.component[v];
    const double s = point(xyz, v).dot(axes[c].col(0));
    if (s < lowest[c]) {
      lowest[c] = s;
      source[c] = v;
    }
  }
  const std::vector<double> dist = geodesic_distance(g, xyz, source);
  scalar_fields(g, vertex_gradients(g, xyz, faces, dist), "geodesic", &out);
  return out;
}

}  // namespace curves_detail
}  // namespace dcurve
