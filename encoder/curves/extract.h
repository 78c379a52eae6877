// Automatic curve extraction: partitions every vertex of a triangle mesh into ordered curves
// (consecutive vertices share a mesh edge) and gives each vertex a curve parameter u.
// The papers draw these curves by hand; here they follow a smooth direction field chosen per
// connected component (see encoder/curves/direction_fields.h), so they are long and straight.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// How u runs along a curve. Both give u = 0 at the first vertex, non-decreasing values, and
// u = 1 at the last vertex of an open curve; on a closed curve the closing step is counted,
// so the last vertex sits below 1 and u = 1 is the first vertex again.
enum class ParamRule {
  ChordLength,      // cumulative Euclidean length on the rest pose
  CoordinateRange,  // 2022 paper eq. (10) on the curve's widest axis: cumulative |dw| on that axis
                    // (equals eq. (10) wherever the curve is monotone in w)
};

struct CurveOptions {
  uint32_t target_points = 64;  // desired vertices per curve, >= 2; longer runs are cut evenly
  ParamRule u_rule = ParamRule::ChordLength;
  // How much a bend inside a curve costs against starting a new curve: a turn of angle a
  // costs bend_weight * (1 - cos a) curves (>= 0). 0 favours the fewest, longest curves
  // whatever their hairpins; 1 makes a right angle cost a whole curve (short, straight
  // curves). The default measured on corpus-ext roughly halves the curve count of 1 while
  // mean turning angles grow by a few degrees (notes/curves-readme.md).
  double bend_weight = 0.3;
};

// rest_xyz: vertex_count * 3 finite floats (model units). faces: 3 vertex ids per triangle.
// The mesh must be edge- and vertex-manifold (OpenMesh must accept every face); isolated
// vertices and boundaries are fine. On failure returns false, sets *error, leaves *out alone.
// Deterministic: the same input gives the same curves.
bool extract_curves(const std::vector<float>& rest_xyz, uint32_t vertex_count,
                    const std::vector<uint32_t>& faces, const CurveOptions& options, Curves* out,
                    std::string* error);

// Cuts curve `curve` so that its local vertex index `at` (1 <= at < size) starts a new curve
// inserted right after it; recomputes u of both parts with `rule`. A closed curve becomes one
// open curve rotated to start at `at` instead. curves->u must be parallel to vertices.
// Throws std::invalid_argument on a bad `curve` or `at` (a caller bug, not bad data).
void split_curve(Curves* curves, uint32_t curve, uint32_t at, const std::vector<float>& rest_xyz,
                 ParamRule rule);

// Recomputes u of curve `curve` from rest_xyz with `rule` (used after any edit of a curve).
// curves->u must be parallel to vertices; throws std::invalid_argument otherwise.
void parameterize_curve(Curves* curves, uint32_t curve, const std::vector<float>& rest_xyz,
                        ParamRule rule);

}  // namespace dcurve
