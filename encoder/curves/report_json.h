// CurveReport as JSON, with the key names `dcurve encode --json` prints.
#pragma once
#include <nlohmann/json.hpp>

#include "encoder/curves/report.h"

namespace dcurve {

inline nlohmann::json curve_report_json(const CurveReport& r) {
  return nlohmann::json{{"curves", r.curves},
                        {"mean_points_per_curve", r.mean_points_per_curve},
                        {"median_points_per_curve", r.median_points_per_curve},
                        {"short_curve_vertex_fraction", r.short_curve_vertex_fraction},
                        {"mean_turning_angle_deg", r.mean_turning_angle_deg}};
}

}  // namespace dcurve
