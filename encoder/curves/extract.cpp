#include "encoder/curves/extract.h"

#include <algorithm>
#include <cmath>


#include "encoder/curves/cut_to_target.h"
#include "encoder/curves/direction_fields.h"
#include "encoder/curves/link_paths.h"
#include "encoder/curves/surface_graph.h"

namespace dcurve {
namespace {

using curves_detail::PathLinks;
using curves_detail::SurfaceGraph;

// What a set of curves costs, per component, in the units of cut_to_target.h.
std::vector<double> component_costs(const Curves& curves, const SurfaceGraph& g, const std::vector<float>& xyz,
                                     double bend_weight) {
  std::vector<double> cost(g.component_count, 0.0);
  for (uint32_t c = 0; c < curves.curve_count(); ++c) {
    const uint32_t* v = curves.vertices.data() + curves.offsets[c];
    const uint32_t n = curves.offsets[c + 1] - curves.offsets[c];
    double total = 1.0 + (n < 4 ? curves_detail::kShortCurvePenalty : 0.0);
    for (uint32_t i = 1; i + 1 < n; ++i) total += curves_detail::bend_cost(xyz, v[i - 1], v[i], v[i + 1], bend_weight);
    if (curves.closed[c] && n >= 3) {
      total += curves_detail::bend_cost(xyz, v[n - 2], v[n - 1], v[0], bend_weight);
      total += curves_detail::bend_cost(xyz, v[n - 1], v[0], v[1], bend_weight);
    }
    cost[g.component[v[0]]] += total;
  }
  return cost;
}

}  // namespace

bool extract_curves(const std::vector<float>& rest_xyz, uint32_t vertex_count,
                    const std::vector<uint32_t>& faces, const CurveOptions& options, Curves* out,
                    std::string* error) {
  if (!(options.bend_weight >= 0.0) || !std::isfinite(options.bend_weight)) {
    if (error) *error = "curve extraction: bend_weight must be finite and >= 0";
    return false;
  }
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
    const Curves cut = curves_detail::cut_to_target(paths, rest_xyz, options.target_points, options.bend_weight);
    const std::vector<double> cost = component_costs(cut, graph, rest_xyz, options.bend_weight);
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
  Curves result = curves_detail::cut_to_target(paths, rest_xyz, options.target_points, options.bend_weight);
  result.u.assign(result.vertices.size(), 0.f);
  for (uint32_t c = 0; c < result.curve_count(); ++c) parameterize_curve(&result, c, rest_xyz, options.u_rule);
  *out = std::move(result);
  return true;
}

}  // namespace dcurve
