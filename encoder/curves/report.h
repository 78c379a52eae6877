// Quality figures of a curve partition, and the partition invariant check.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// JSON keys (dcurve encode --json): "curves", "mean_points_per_curve",
// "median_points_per_curve", "short_curve_vertex_fraction", "mean_turning_angle_deg".
struct CurveReport {
  uint32_t curves;
  double mean_points_per_curve;       // vertices / curves
  double median_points_per_curve;     // middle curve size (mean of the two middle ones if even)
  double short_curve_vertex_fraction; // in [0, 1]: vertices on curves of fewer than 4 points
  double mean_turning_angle_deg;      // in [0, 180]: angle between consecutive steps, averaged
                                      // over every vertex with two steps (closed curves wrap)
};

// rest_xyz: vertex_count * 3 floats covering every id in curves.vertices. All zero when empty.
CurveReport curve_report(const Curves& curves, const std::vector<float>& rest_xyz);

// Checks the partition invariant; false + message when broken (used by tests and the encoder's
// self-checks): sizes consistent, every vertex 0..vertex_count-1 exactly once, consecutive
// vertices share an edge of `faces`, a closed curve has >= 3 vertices and its last vertex
// shares an edge with its first, u finite in [0, 1] and non-decreasing along each curve.
bool check_partition(const Curves& curves, uint32_t vertex_count, const std::vector<uint32_t>& faces,
                     std::string* error);

}  // namespace dcurve
