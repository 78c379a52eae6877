#include "codec/common/render_mesh.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace dcurve {

const char* attribute_gltf_name(AttributeSemantic s) {
  switch (s) {
    case AttributeSemantic::TexCoord0: return "TEXCOORD_0";
    case AttributeSemantic::TexCoord1: return "TEXCOORD_1";
    case AttributeSemantic::Color0: return "COLOR_0";
    case AttributeSemantic::Normal: return "NORMAL";
  }
  return "unknown";
}

bool attribute_components_allowed(AttributeSemantic s, uint32_t components) {
  switch (s) {
    case AttributeSemantic::TexCoord0:
    case AttributeSemantic::TexCoord1: return components == 2;
    case AttributeSemantic::Color0: return components == 3 || components == 4;
    case AttributeSemantic::Normal: return components == 3;
  }
  return false;
}

bool render_source_in_first_use_order(const std::vector<uint32_t>& source, uint32_t vertex_count) {
  uint32_t next = 0;
  for (uint32_t v : source) {
    if (v > next) return false;
    if (v == next) ++next;
  }
  return next == vertex_count;
}

void render_copies(const std::vector<uint32_t>& source, uint32_t vertex_count, std::vector<uint32_t>* offsets,
                   std::vector<uint32_t>* copies) {
  offsets->assign(size_t(vertex_count) + 1, 0);
  for (uint32_t v : source) ++(*offsets)[size_t(v) + 1];
  for (size_t v = 0; v < vertex_count; ++v) (*offsets)[v + 1] += (*offsets)[v];
  std::vector<uint32_t> fill(offsets->begin(), offsets->end() - 1);
  copies->resize(source.size());
  for (size_t r = 0; r < source.size(); ++r) (*copies)[fill[source[r]]++] = uint32_t(r);
}

bool render_corners_from_ordinals(const std::vector<uint32_t>& faces, const std::vector<uint32_t>& source,
                                  uint32_t vertex_count, const std::vector<uint32_t>& ordinals,
                                  std::vector<uint32_t>* corners) {
  if (ordinals.size() != faces.size()) return false;
  std::vector<uint32_t> offsets, copies;
  render_copies(source, vertex_count, &offsets, &copies);
  corners->resize(faces.size());
  for (size_t k = 0; k < faces.size(); ++k) {
    const uint32_t v = faces[k];
    if (v >= vertex_count || ordinals[k] >= offsets[v + 1] - offsets[v]) return false;
    (*corners)[k] = copies[offsets[v] + ordinals[k]];
  }
  return true;
}

bool render_corner_ordinals(const std::vector<uint32_t>& faces, const RenderMesh& render, uint32_t vertex_count,
                            std::vector<uint32_t>* ordinals) {
  if (render.corners.size() != faces.size()) return false;
  std::vector<uint32_t> offsets, copies;
  render_copies(render.source, vertex_count, &offsets, &copies);
  ordinals->resize(faces.size());
  for (size_t k = 0; k < faces.size(); ++k) {
    const uint32_t v = faces[k], r = render.corners[k];
    if (v >= vertex_count || r >= render.source.size() || render.source[r] != v) return false;
    const auto first = copies.begin() + offsets[v], last = copies.begin() + offsets[v + 1];
    (*ordinals)[k] = uint32_t(std::lower_bound(first, last, r) - first);
  }
  return true;
}

}  // namespace dcurve
