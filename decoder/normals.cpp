#include "normals.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace dcurve {

void area_normals(const float* xyz, const uint32_t* faces, size_t corner_count, const uint32_t* targets,
                  size_t target_count, float* out) {
  std::fill_n(out, target_count * 3, 0.f);
  for (size_t t = 0; t + 2 < corner_count; t += 3) {
    const float* p0 = xyz + 3 * size_t(faces[t]);
    const float* p1 = xyz + 3 * size_t(faces[t + 1]);
    const float* p2 = xyz + 3 * size_t(faces[t + 2]);
    const float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    const float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    // The unnormalized cross product weights each face by its area.
    const float c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (size_t k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) out[3 * size_t(targets[t + k]) + a] += c[a];
  }
  for (size_t v = 0; v < target_count; ++v) {
    float* n = out + 3 * v;
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.f)
      for (int a = 0; a < 3; ++a) n[a] /= len;
  }
}

}  // namespace dcurve
