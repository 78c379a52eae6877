#include "python/render_input.h"

#include <cstring>

namespace dcurve::python {
namespace {

// The values of all attributes at one corner, side by side: what makes two corners one copy.
std::vector<float> corner_key(const std::vector<CornerAttribute>& attributes, size_t corner) {
  std::vector<float> key;
  for (const CornerAttribute& a : attributes)
    key.insert(key.end(), a.values.begin() + std::ptrdiff_t(corner * a.components),
               a.values.begin() + std::ptrdiff_t((corner + 1) * a.components));
  return key;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Per vertex, the first corner of each of its distinct keys, in order of first use; and per
// corner, which of its vertex's copies it takes.
void find_copies(const std::vector<uint32_t>& faces, uint32_t vertex_count, const std::vector<CornerAttribute>& attributes,
                 std::vector<std::vector<size_t>>* first_corner, std::vector<uint32_t>* ordinal) {
  first_corner->assign(vertex_count, {});
  ordinal->resize(faces.size());
  std::vector<std::vector<std::vector<float>>> keys(vertex_count);
  for (size_t k = 0; k < faces.size(); ++k) {
    const uint32_t v = faces[k];
    std::vector<float> key = corner_key(attributes, k);
    size_t i = 0;
    while (i < keys[v].size() && !same_bits(keys[v][i], key)) ++i;
    if (i == keys[v].size()) {
      keys[v].push_back(std::move(key));
      (*first_corner)[v].push_back(k);
    }
    (*ordinal)[k] = uint32_t(i);
  }
}

}  // namespace

void weld_corner_attributes(const std::vector<uint32_t>& faces, uint32_t vertex_count,
                            const std::vector<CornerAttribute>& attributes, AnimationRender* render) {
  std::vector<std::vector<size_t>> first_corner;
  std::vector<uint32_t> ordinal;
  find_copies(faces, vertex_count, attributes, &first_corner, &ordinal);
  render->source.clear();
  render->attributes.clear();
  for (const CornerAttribute& a : attributes) render->attributes.push_back({a.semantic, a.components, {}});
  std::vector<uint32_t> first_render(vertex_count);
  for (uint32_t v = 0; v < vertex_count; ++v) {
    first_render[v] = uint32_t(render->source.size());
    const size_t copies = first_corner[v].empty() ? 1 : first_corner[v].size();
    for (size_t c = 0; c < copies; ++c) {
      render->source.push_back(v);
      for (size_t i = 0; i < attributes.size(); ++i) {
        const CornerAttribute& a = attributes[i];
        std::vector<float>& out = render->attributes[i].values;
        if (first_corner[v].empty()) {
          out.insert(out.end(), a.components, 0.f);
        } else {
          const auto from = a.values.begin() + std::ptrdiff_t(first_corner[v][c] * a.components);
          out.insert(out.end(), from, from + a.components);
        }
      }
    }
  }
  render->corners.resize(faces.size());
  for (size_t k = 0; k < faces.size(); ++k) render->corners[k] = first_render[faces[k]] + ordinal[k];
}

}  // namespace dcurve::python
