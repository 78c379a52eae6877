// glTF 2.0 out (.glb, or .gltf with the buffer embedded as base64): frame 0 as the mesh,
// every later frame as a morph target (its offset from frame 0), and an animation of the
// weights with one key per frame, so standard viewers play the frames in order and blend
// linearly between them.
//
// Streamed in bounded memory: every byte offset follows from the counts, so the buffer is
// written as the frames arrive (a .glb reserves room for its JSON, whose only unknowns are
// the targets' bounds, and fills it in at the end; a .gltf puts its buffer first in the JSON
// and the rest after it). Memory holds frame 0, one frame and a few numbers per frame.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/common/render_mesh.h"
#include "encoder/io/output_file.h"

namespace dcurve {

struct TargetText;

// What the output carries besides the frames: static attributes written once (TEXCOORD_0,
// COLOR_0, ... per vertex of the output), and the input's placement: node transform and
// name, mesh name, the first key's time.
struct GltfScene {
  struct Attribute {
    std::string name;      // glTF attribute name
    uint32_t components;   // 2, 3 or 4
    std::vector<float> values;
  };
  std::vector<Attribute> attributes;
  Placement placement;
  bool normals = false;  // each frame comes with its normals (NORMAL and the targets' NORMAL)
  // Face groups, one primitive each: the writer's faces are ordered by group, group g's
  // group_faces[g] triangles drawn with material group_materials[g] (-1: none).
  std::vector<uint32_t> group_faces;
  std::vector<int> group_materials;
  // The materials, textures, samplers and images (MATL's JSON) and the images' bytes.
  std::string materials_json;
  std::vector<MaterialImage> images;
};

class GltfWriter {
 public:
  // Frames arrive in order through add_frame; `faces` empty writes a point primitive;
  // `binary`: .glb, else .gltf.
  GltfWriter(uint32_t vertex_count, std::vector<uint32_t> faces, uint32_t frame_count, double frame_rate, bool binary,
             GltfScene scene = {});

  // The most bytes the file can take (exact but for the bounds' digits), and false with a
  // message when that is over the 1 GiB dcurve writes (every frame is a full target, the
  // weights grow with frames squared, base64 adds a third). Checked before any decoding.
  static uint64_t file_bytes(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, bool binary,
                             const GltfScene& scene = {});
  static bool check_size(uint32_t vertex_count, size_t face_ids, uint32_t frame_count, bool binary, std::string* error,
                         const GltfScene& scene = {});

  // Creates the output (OutputFile) and writes what precedes frame 0.
  bool open(const std::string& path, bool replace, std::string* error);
  bool add_frame(const float* xyz, std::string* error, const float* normals = nullptr);
  // Writes the animation and the JSON, then moves the file into place.
  bool finish(std::string* error);

 private:
  bool put(const void* data, size_t size, std::string* error);
  bool flush(bool last, std::string* error);
  bool write_animation_data(std::string* error);
  std::string json(bool placeholders) const;
  TargetText target_text(int view_index, uint64_t first_accessor, bool placeholders) const;
  uint64_t buffer_bytes() const;
  uint64_t expected_bytes() const;        // file_bytes of this writer
  bool fits(std::string* error) const;    // check_size of this writer
  uint64_t static_bytes() const;
  float key_time(uint32_t frame) const;  // the input's first key time, then one frame apart

  uint32_t vertex_count_, frame_count_;
  double frame_rate_;
  bool binary_;
  std::vector<uint32_t> faces_;
  GltfScene scene_;
  std::vector<float> base_;                     // frame 0
  std::vector<std::array<float, 6>> bounds_;    // per frame: min xyz, max xyz (of the target)
  uint32_t frames_added_ = 0;
  uint64_t json_room_ = 0;                      // .glb: bytes reserved for the JSON
  OutputFile out_;
  std::vector<uint8_t> pending_;                // binary bytes not written yet (base64: groups of 3)
};

}  // namespace dcurve
