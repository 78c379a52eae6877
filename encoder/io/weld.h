// Copies of a vertex at UV and normal seams, made one vertex again. Exporters split a vertex
// wherever its texture coordinates or normals differ (Blender's cloth: 3,052 render vertices
// for 2,401 positions); coded apart, the copies would drift apart by up to the tolerance and
// open cracks. Welded, each position is coded once and the copies are render vertices
// (Animation::render) that show it.
#pragma once
#include <vector>

#include "encoder/animation.h"

namespace dcurve {

// `anim` holds render vertices (faces over them, frames of them) and `attributes` their
// static attributes (values per render vertex). Vertices equal in every frame, bit for bit,
// become one, numbered in order of first appearance; anim->render maps the render vertices
// (in their input order) to them and keeps the attributes. Triangles left with a vertex
// twice (zero area in every frame) are dropped with a note (and from render.face_group).
// Without copies, attributes or groups anim->render stays empty.
void weld_copies(Animation* anim, std::vector<AnimationRender::Attribute> attributes);

}  // namespace dcurve
