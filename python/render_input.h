// Render vertices from attributes given per corner, as a DCC holds them (Blender's UV layers
// are per loop): each vertex gets one render vertex per distinct combination of its corners'
// values, so a UV seam splits it and everything else stays one vertex.
#pragma once
#include <cstdint>
#include <vector>

#include "encoder/animation.h"

namespace dcurve::python {

// Per corner of the faces: `components` floats each (corner_count * components).
struct CornerAttribute {
  AttributeSemantic semantic = AttributeSemantic::TexCoord0;
  uint32_t components = 2;
  std::vector<float> values;
};

// Fills render->source, corners and attributes for `faces` over `vertex_count` vertices:
// render vertices numbered vertex after vertex (so in first-use order of `source`), each
// vertex's copies in order of first use; a vertex no face uses gets one copy of zeros.
void weld_corner_attributes(const std::vector<uint32_t>& faces, uint32_t vertex_count,
                            const std::vector<CornerAttribute>& attributes, AnimationRender* render);

}  // namespace dcurve::python
