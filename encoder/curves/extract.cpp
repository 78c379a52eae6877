#include "encoder/curves/extract.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "encoder/curves/direction_fields.h"
#include "encoder/curves/link_paths.h"
#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace {

using curves_detail::PathLinks;
using curves_detail::SurfaceGraph;

// What a set of paths would cost the codec, per component, in units of "one curve": each
// curve after cutting to the target length, plus its bends (a 90-degree turn counts as one
// more curve, since the predictor from the previous vertex fails there about as badly as at a
// curve start).
std::vector<double> component_costs(const Curves& paths, const SurfaceGraph& g, const std::vector<float>& xyz,
                                     uint32_t target) {
  std::vector<double> cost(g.component_count, 0.0);
  for (uint32_t c = 0; c < paths.curve_count(); ++c) {
    const uint32_t* v = paths.vertices.data() + paths.offsets[c];
    const uint32_t n = paths.offsets[c + 1] - paths.offsets[c];
    double bends = 0.0;
    for (uint32_t i = 1; i + 1 < n; ++i) bends += 1.0 - std::cos(curves_detail::turn_angle(xyz, v[i - 1], v[i], v[i + 1]));
    if (paths.closed[c] && n >= 3) {
      bends += 1.0 - std::cos(curves_detail::turn_angle(xyz, v[n - 2], v[n - 1], v[0]));
      bends += 1.0 - std::cos(curves_detail::turn_angle(xyz, v[n - 1], v[0], v[1]));
    }
    cost[g.component[v[0]]] += double((n + target - 1) / target) + bends;
  }
  return cost;
}

// Cuts every path longer than `target` into ceil(n / target) nearly equal open pieces.
Curves cut_to_target(const Curves& paths, uint32_t target) {
  Curves out;
  out.vertices = paths.vertices;
  out.offsets.assign(1, 0);
  for (uint32_t c = 0; c < paths.curve_count(); ++c) {
    const uint32_t begin = paths.offsets[c], n = paths.offsets[c + 1] - begin;
    const uint32_t pieces = (n + target - 1) / target;
    if (pieces <= 1) {
      out.offsets.push_back(begin + n);
      out.closed.push_back(paths.closed[c]);
      continue;
    }
    for (uint32_t p = 1; p <= pieces; ++p) {
      out.offsets.push_back(begin + uint32_t(uint64_t(n) * p / pieces));
      out.closed.push_back(0);
    }
  }
  return out;
}

}  // namespace

bool extract_curves(const std::vector<float>& rest_xyz, uint32_t vertex_count,
                    const std::vector<uint32_t>& faces, const CurveOptions& options, Curves* out,
                    std::string* error) {
  if (options.target_points < 2) {
    if (error) *error = "curve extraction: target_points must be >= 2 (got " + std::to_string(options.target_points) + ")";
    return false;
  }
  SurfaceGraph graph;
  if (!curves_detail::build_surface_graph(rest_xyz, vertex_count, faces, &graph, error)) return false;

  const std::vector<curves_detail::DirectionField> fields = curves_detail::candidate_fields(graph, rest_xyz, faces);
  const curves_detail::LinkParams params;
  std::vector<double> best_cost(graph.component_count, HUGE_VAL);
  std::vector<uint32_t> best_field(graph.component_count, 0);
  std::vector<PathLinks> links;
  links.reserve(fields.size());
  Curves paths;
  for (uint32_t f = 0; f < fields.size(); ++f) {
    links.push_back(curves_detail::link_along_field(graph, rest_xyz, fields[f].dir, params));
    curves_detail::assemble_paths(links.back(), &paths);
    const std::vector<double> cost = component_costs(paths, graph, rest_xyz, options.target_points);
    for (uint32_t c = 0; c < graph.component_count; ++c)
      if (cost[c] < best_cost[c]) {  // strict: the earlier field wins ties
        best_cost[c] = cost[c];
        best_field[c] = f;
      }
  }
  // Components never share an edge, so each keeps the links of its own best field.
  PathLinks chosen;
  chosen.nbr.resize(size_t(vertex_count) * 2);
  for (uint32_t v = 0; v < vertex_count; ++v) {
    const PathLinks& from = links[best_field[graph.component[v]]];
    chosen.nbr[2 * v] = from.nbr[2 * v];
    chosen.nbr[2 * v + 1] = from.nbr[2 * v + 1];
  }
  curves_detail::assemble_paths(chosen, &paths);
  Curves result = cut_to_target(paths, options.target_points);
  result.u.assign(result.vertices.size(), 0.f);
  for (uint32_t c = 0; c < result.curve_count(); ++c) parameterize_curve(&result, c, rest_xyz, options.u_rule);
  *out = std::move(result);
  return true;
}

}  // namespace dcurve
