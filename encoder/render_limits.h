// What the REND, PLAC and MATL readers accept of the input's names and media types, checked
// before encoding: a name past the format's limit would be written, then refused on reading
// back as a malformed section.
#pragma once
#include <string>

#include "encoder/animation.h"

namespace dcurve {

// False, naming the text (quoted and cut) and the limit, when a group, mesh or node name is
// over render_format::kMaxNameBytes or an image's media type over kMaxMimeBytes.
bool check_render_limits(const Animation& anim, std::string* error);

}  // namespace dcurve
