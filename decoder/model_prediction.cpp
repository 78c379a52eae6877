#include "model_prediction.h"

#include <algorithm>
#include <cmath>

#include "frame_evaluator.h"

namespace dcurve {

bool has_motion_model(const Model& model) {
  for (const Segment& s : model.segments)
    for (const CurveMotion& m : s.motion)
      if (m.basis != Basis::Zero) return true;
  return false;
}

bool model_grid_prediction(const Model& model, uint64_t max_floats, std::vector<int32_t>* out, std::string* error) {
  FrameEvaluator model_only;
  if (!model_only.build(model, {}, max_floats, error)) return false;
  const size_t n = size_t(model.meta.vertex_count) * 3;
  const ResidualLayer& grid = model.residual;
  out->resize(n * model.meta.frame_count);
  std::vector<float> xyz(n);
  // Far outside any sane grid; keeps the residual arithmetic inside int64 on hostile files.
  constexpr double kLimit = double(1 << 30);
  for (uint32_t f = 0; f < model.meta.frame_count; ++f) {
    model_only.evaluate(double(f), xyz.data());
    int32_t* qf = out->data() + f * n;
    for (size_t i = 0; i < n; ++i) {
      double g = std::nearbyint((double(xyz[i]) - grid.origin[i % 3]) / grid.step);
      qf[i] = int32_t(std::clamp(std::isfinite(g) ? g : 0.0, -kLimit, kLimit));
    }
  }
  return true;
}

}  // namespace dcurve
