// The file's render vertices (REND) from the input's: corners follow the faces as the file
// stores them (the face coder reorders and rotates triangles), attributes quantized.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"
#include "encoder/animation.h"

namespace dcurve {

// Bits per component, over each component's range in the input (format_spec/dcrv.md section 19).
struct AttributePrecision {
  uint8_t texcoord_bits = 14;  // 1/16383 of the UV range: well below a texel of a 4K texture
  uint8_t color_bits = 12;     // above the 8 bits colours usually come in
  uint8_t normal_bits = 12;    // per component over [-1, 1]: about 0.03 degrees
};

// model.render for the faces `file_faces` (the same triangles as anim.faces, in any order
// and rotation). Empty when the input has no render vertices.
RenderMesh build_render_mesh(const Animation& anim, const std::vector<uint32_t>& file_faces,
                             const AttributePrecision& precision);

// Quantizes `values` (count * components) with `bits` per component over their range.
RenderAttribute quantize_attribute(AttributeSemantic semantic, uint32_t components, const std::vector<float>& values,
                                   uint8_t bits);

}  // namespace dcurve
