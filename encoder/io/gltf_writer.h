// glTF 2.0 out (.glb or .gltf, written by tinygltf): frame 0 as the mesh, every later frame
// as a morph target (its offset from frame 0), and an animation of the weights with one key
// per frame, so standard viewers play the frames in order and blend linearly between them.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

class GltfWriter {
 public:
  // Frames arrive in order through add_frame; `faces` empty writes a point primitive.
  GltfWriter(uint32_t vertex_count, std::vector<uint32_t> faces, uint32_t frame_count, double frame_rate);

  // False (with a message) when the file would be too large for one glTF buffer: every frame
  // is a full target and the weights grow with frames squared. Checked before any decoding.
  static bool check_size(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, std::string* error);

  void add_frame(const float* xyz);

  // Writes the file atomically; the format follows the extension (.glb binary, else .gltf
  // with the buffer embedded).
  bool write(const std::string& path, std::string* error) const;

 private:
  uint32_t vertex_count_, frame_count_;
  double frame_rate_;
  std::vector<uint32_t> faces_;
  std::vector<float> base_, targets_;  // frame 0; frames 1.. minus frame 0
  uint32_t frames_added_ = 0;
};

}  // namespace dcurve
