#include "encoder/render_limits.h"

#include <cstddef>
#include <string>

#include "codec/common/error.h"
#include "codec/common/render_format.h"
#include "encoder/io/quoted_text.h"

namespace dcurve {
namespace {

bool check_length(const char* what, const std::string& text, size_t limit, std::string* error) {
  if (text.size() <= limit) return true;
  return fail(error, std::string(what) + " \"" + quote_file_text(text) + "\" is " + std::to_string(text.size()) +
                         " bytes, more than the " + std::to_string(limit) + " a .dcrv holds");
}

}  // namespace

bool check_render_limits(const Animation& anim, std::string* error) {
  using render_format::kMaxMimeBytes;
  using render_format::kMaxNameBytes;
  if (!anim.render.empty()) {  // groups and materials are written with render vertices only
    for (const FaceGroup& g : anim.render.groups)
      if (!check_length("material name", g.name, kMaxNameBytes, error)) return false;
    for (const MaterialImage& image : anim.materials.images)
      if (!check_length("image media type", image.mime_type, kMaxMimeBytes, error)) return false;
  }
  return check_length("mesh name", anim.placement.mesh_name, kMaxNameBytes, error) &&
         check_length("node name", anim.placement.node_name, kMaxNameBytes, error);
}

}  // namespace dcurve
