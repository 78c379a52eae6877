#include "encoder/fit/curve_frames.h"

#include <cmath>
#include <string>

namespace dcurve {

CurveFrames gather_curve_frames(const Animation& anim, const Curves& curves, uint32_t curve,
                                const std::vector<uint32_t>& frames, const std::vector<double>& tau) {
  CurveFrames c;
  const uint32_t begin = curves.offsets[curve], end = curves.offsets[curve + 1];
  for (uint32_t k = begin; k < end; ++k) c.u.push_back(double(curves.u[k]));
  c.tau = tau;
  c.xyz.reserve(size_t(end - begin) * frames.size() * 3);
  for (uint32_t f : frames)
    for (uint32_t k = begin; k < end; ++k)
      for (int a = 0; a < 3; ++a) c.xyz.push_back(double(anim.frames[f][size_t(curves.vertices[k]) * 3 + size_t(a)]));
  return c;
}

bool validate_curves_for(const Animation& anim, const Curves& curves, std::string* error) {
  auto fail = [&](const std::string& m) {
    if (error) *error = "curves: " + m;
    return false;
  };
  if (curves.offsets.empty() || curves.offsets.front() != 0 || curves.offsets.back() != curves.vertices.size())
    return fail("offsets must run from 0 to the vertex list size");
  for (size_t c = 1; c < curves.offsets.size(); ++c)
    if (curves.offsets[c] < curves.offsets[c - 1]) return fail("offsets must not decrease");
  if (curves.u.size() != curves.vertices.size()) return fail("u must be parallel to the vertex list");
  for (uint32_t v : curves.vertices)
    if (v >= anim.vertex_count) return fail("vertex id " + std::to_string(v) + " out of range");
  for (float u : curves.u)
    if (!(u >= 0.f && u <= 1.f)) return fail("u must lie in [0, 1]");
  return true;
}

}  // namespace dcurve
