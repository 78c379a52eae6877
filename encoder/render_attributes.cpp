#include "encoder/render_attributes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

namespace dcurve {
namespace {

using Triangle = std::array<uint32_t, 3>;

Triangle sorted(const uint32_t* t) {
  Triangle s = {t[0], t[1], t[2]};
  std::sort(s.begin(), s.end());
  return s;
}

// The rotation r with file[k] == input[(k + r) % 3], or -1.
int rotation(const uint32_t* file, const uint32_t* input) {
  for (int r = 0; r < 3; ++r)
    if (file[0] == input[r] && file[1] == input[(r + 1) % 3] && file[2] == input[(r + 2) % 3]) return r;
  return -1;
}

// Per corner of file_faces, the corner of input_faces it came from.
std::vector<size_t> match_corners(const std::vector<uint32_t>& input_faces, const std::vector<uint32_t>& file_faces) {
  std::map<Triangle, std::vector<size_t>> by_vertices;  // input triangles, last first
  for (size_t t = input_faces.size() / 3; t-- > 0;) by_vertices[sorted(&input_faces[3 * t])].push_back(t);
  std::vector<size_t> from(file_faces.size());
  for (size_t t = 0; t < file_faces.size() / 3; ++t) {
    std::vector<size_t>& candidates = by_vertices[sorted(&file_faces[3 * t])];
    for (size_t i = candidates.size(); i-- > 0;) {
      const int r = rotation(&file_faces[3 * t], &input_faces[3 * candidates[i]]);
      if (r < 0) continue;
      for (int k = 0; k < 3; ++k) from[3 * t + k] = 3 * candidates[i] + size_t((k + r) % 3);
      candidates.erase(candidates.begin() + std::ptrdiff_t(i));
      break;
    }
  }
  return from;
}

uint8_t bits_for(AttributeSemantic s, const AttributePrecision& p) {
  switch (s) {
    case AttributeSemantic::TexCoord0:
    case AttributeSemantic::TexCoord1: return p.texcoord_bits;
    case AttributeSemantic::Color0: return p.color_bits;
    case AttributeSemantic::Normal: return p.normal_bits;
  }
  return p.texcoord_bits;
}

}  // namespace

RenderAttribute quantize_attribute(AttributeSemantic semantic, uint32_t components, const std::vector<float>& values,
                                   uint8_t bits) {
  RenderAttribute a;
  a.semantic = semantic;
  a.components = uint8_t(components);
  a.bits = bits;
  const size_t count = values.size() / components;
  for (uint32_t c = 0; c < components; ++c) {
    a.lo[c] = a.hi[c] = count ? values[c] : 0.f;
    for (size_t i = 0; i < count; ++i) {
      a.lo[c] = std::min(a.lo[c], values[i * components + c]);
      a.hi[c] = std::max(a.hi[c], values[i * components + c]);
    }
  }
  const double top = double((1u << bits) - 1);
  a.q.resize(values.size());
  for (size_t i = 0; i < values.size(); ++i) {
    const uint32_t c = uint32_t(i % components);
    const double range = double(a.hi[c]) - double(a.lo[c]);
    a.q[i] = range > 0 ? uint16_t(std::lround((double(values[i]) - a.lo[c]) / range * top)) : 0;
  }
  return a;
}

RenderMesh build_render_mesh(const Animation& anim, const std::vector<uint32_t>& file_faces,
                             const AttributePrecision& precision) {
  RenderMesh out;
  if (anim.render.empty() || file_faces.empty()) return out;
  out.source = anim.render.source;
  const std::vector<size_t> from = match_corners(anim.faces, file_faces);
  out.corners.resize(file_faces.size());
  for (size_t k = 0; k < file_faces.size(); ++k) out.corners[k] = anim.render.corners[from[k]];
  out.groups = anim.render.groups;
  if (!out.groups.empty())
    for (size_t t = 0; t < file_faces.size() / 3; ++t) out.face_group.push_back(anim.render.face_group[from[3 * t] / 3]);
  for (const AnimationRender::Attribute& a : anim.render.attributes)
    out.attributes.push_back(quantize_attribute(a.semantic, a.components, a.values, bits_for(a.semantic, precision)));
  return out;
}

}  // namespace dcurve
