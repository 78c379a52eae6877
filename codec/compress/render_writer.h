// Writing the REND, PLAC and MATL sections' payloads (codec/common/render_mesh.h says what they
// hold; codec/decompress/render_reader.h reads them back).
#pragma once
#include <cstdint>
#include <vector>

#include "codec/common/model.h"

namespace dcurve {

// Raw REND payload of model.render (non-empty, canonical numbering, model.faces present).
std::vector<uint8_t> render_bytes(const Model& model);
// Raw MATL payload of model.materials.
std::vector<uint8_t> material_bytes(const Model& model);
// Raw PLAC payload of model.placement.
std::vector<uint8_t> placement_bytes(const Model& model);

}  // namespace dcurve
