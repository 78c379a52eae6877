// The encoder's input: an animated triangle mesh with fixed connectivity. Readers
// (encoder/io), the simulation (corpus/sim) and tests produce it; encode_animation takes it.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"

namespace dcurve {

// Render vertices of the input, when a reader found copies of a vertex (UV or normal seams)
// or static attributes; empty otherwise. The encoder stores them in REND
// (codec/common/render_mesh.h), quantized.
struct AnimationRender {
  struct Attribute {
    AttributeSemantic semantic = AttributeSemantic::TexCoord0;
    uint32_t components = 2;
    std::vector<float> values;  // source.size() * components
  };
  std::vector<uint32_t> source;   // per render vertex: the vertex whose position it shows
  std::vector<uint32_t> corners;  // per corner of Animation::faces: its render vertex
  std::vector<Attribute> attributes;
  std::vector<FaceGroup> groups;     // one per material of the input; empty: none
  std::vector<uint32_t> face_group;  // per triangle of Animation::faces, with groups
  bool empty() const { return source.empty(); }
};

struct Animation {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> faces;              // 3 vertex ids per triangle, shared by all frames
  std::vector<std::vector<float>> frames;   // per frame: vertex_count * 3 floats (x, y, z)
  double frame_rate = 30.0;                 // frames per second
  AnimationRender render;
  Placement placement;                      // where and when the input placed the animation
  MaterialSet materials;                    // what the render groups draw with
  std::vector<std::string> notes;           // what a reader read but does not keep, for the user
};

}  // namespace dcurve
