// The encoder's input: an animated triangle mesh with fixed connectivity. Readers
// (encoder/io), the simulation (corpus/sim) and tests produce it; encode_animation takes it.
#pragma once
#include <cstdint>
#include <vector>

namespace dcurve {

struct Animation {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> faces;              // 3 vertex ids per triangle, shared by all frames
  std::vector<std::vector<float>> frames;   // per frame: vertex_count * 3 floats (x, y, z)
  double frame_rate = 30.0;                 // frames per second
};

}  // namespace dcurve
