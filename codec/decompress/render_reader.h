// Reading the REND, PLAC and MATL sections' payloads, as codec/compress/render_writer.h wrote them.
#pragma once
#include "codec/common/bytes.h"
#include "codec/common/model.h"

namespace dcurve {

// REND into model->render; needs META and FACE read first (false without faces). False on
// any rejection of format_spec/dcrv.md section 19; never allocates more than the payload's
// bytes can fill.
bool parse_render(ByteReader& r, Model* model);
// MATL into model->materials (section 21).
bool parse_materials(ByteReader& r, Model* model);
// PLAC into model->placement (section 20).
bool parse_placement(ByteReader& r, Model* model);

}  // namespace dcurve
