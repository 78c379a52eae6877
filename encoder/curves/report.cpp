#include "encoder/curves/report.h"

#include <algorithm>
#include <cmath>

#include "encoder/curves/link_paths.h"

namespace dcurve {
namespace {

bool fail(std::string* error, const std::string& msg) {
  if (error) *error = "curve partition: " + msg;
  return false;
}

uint64_t edge_key(uint32_t a, uint32_t b) {
  return (uint64_t(std::min(a, b)) << 32) | std::max(a, b);
}

}  // namespace

CurveReport curve_report(const Curves& curves, const std::vector<float>& rest_xyz) {
  CurveReport r{};
  r.curves = curves.curve_count();
  if (r.curves == 0) return r;
  std::vector<uint32_t> sizes(r.curves);
  size_t short_vertices = 0, turns = 0;
  double turn_sum = 0.0;
  for (uint32_t c = 0; c < r.curves; ++c) {
    const uint32_t n = curves.offsets[c + 1] - curves.offsets[c];
    const uint32_t* v = curves.vertices.data() + curves.offsets[c];
    sizes[c] = n;
    if (n < 4) short_vertices += n;
    for (uint32_t i = 1; i + 1 < n; ++i, ++turns) turn_sum += curves_detail::turn_angle(rest_xyz, v[i - 1], v[i], v[i + 1]);
    if (curves.closed[c] && n >= 3) {
      turn_sum += curves_detail::turn_angle(rest_xyz, v[n - 2], v[n - 1], v[0]);
      turn_sum += curves_detail::turn_angle(rest_xyz, v[n - 1], v[0], v[1]);
      turns += 2;
    }
  }
  const size_t total = curves.vertices.size();
  r.mean_points_per_curve = double(total) / r.curves;
  std::sort(sizes.begin(), sizes.end());
  r.median_points_per_curve = r.curves % 2 ? sizes[r.curves / 2]
                                           : 0.5 * (double(sizes[r.curves / 2 - 1]) + sizes[r.curves / 2]);
  r.short_curve_vertex_fraction = total ? double(short_vertices) / total : 0.0;
  r.mean_turning_angle_deg = turns ? turn_sum / turns * 180.0 / M_PI : 0.0;
  return r;
}

bool check_partition(const Curves& curves, uint32_t vertex_count, const std::vector<uint32_t>& faces,
                     std::string* error) {
  const uint32_t C = curves.curve_count();
  if (curves.offsets.empty() || curves.offsets[0] != 0) return fail(error, "offsets must start with 0");
  if (curves.vertices.size() != vertex_count)
    return fail(error, "holds " + std::to_string(curves.vertices.size()) + " vertices, mesh has " +
                           std::to_string(vertex_count));
  if (curves.offsets.back() != curves.vertices.size()) return fail(error, "last offset differs from the vertex count");
  if (curves.closed.size() != C) return fail(error, "closed flags differ from the curve count");
  if (curves.u.size() != curves.vertices.size()) return fail(error, "u differs in size from vertices");
  std::vector<uint8_t> seen(vertex_count, 0);
  for (uint32_t v : curves.vertices) {
    if (v >= vertex_count) return fail(error, "vertex id " + std::to_string(v) + " out of range");
    if (seen[v]++) return fail(error, "vertex " + std::to_string(v) + " lies on more than one curve position");
  }
  std::vector<uint64_t> edges;
  edges.reserve(faces.size());
  for (size_t t = 0; t + 2 < faces.size(); t += 3)
    for (int k = 0; k < 3; ++k) edges.push_back(edge_key(faces[t + k], faces[t + (k + 1) % 3]));
  std::sort(edges.begin(), edges.end());
  auto adjacent = [&](uint32_t a, uint32_t b) { return std::binary_search(edges.begin(), edges.end(), edge_key(a, b)); };

  for (uint32_t c = 0; c < C; ++c) {
    const uint32_t begin = curves.offsets[c], end = curves.offsets[c + 1];
    const std::string name = "curve " + std::to_string(c);
    if (end <= begin) return fail(error, name + " is empty or its offsets decrease");
    for (uint32_t i = begin; i < end; ++i) {
      const float u = curves.u[i];
      if (!std::isfinite(u) || u < 0.f || u > 1.f) return fail(error, name + ": u outside [0, 1]");
      if (i > begin && u < curves.u[i - 1]) return fail(error, name + ": u decreases at position " + std::to_string(i - begin));
      if (i > begin && !adjacent(curves.vertices[i - 1], curves.vertices[i]))
        return fail(error, name + ": vertices " + std::to_string(curves.vertices[i - 1]) + " and " +
                               std::to_string(curves.vertices[i]) + " share no mesh edge");
    }
    if (curves.closed[c] > 1) return fail(error, name + ": closed flag is neither 0 nor 1");
    if (curves.closed[c]) {
      if (end - begin < 3) return fail(error, name + " is closed with fewer than 3 vertices");
      if (!adjacent(curves.vertices[end - 1], curves.vertices[begin]))
        return fail(error, name + " is closed but its last vertex shares no edge with its first");
    }
  }
  return true;
}

}  // namespace dcurve
