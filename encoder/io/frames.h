// Animated meshes in and out: a folder of OBJ/PLY/OFF frames with fixed connectivity,
// read and written through OpenMesh's IO. Vertex order is never changed.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

struct Animation {
  uint32_t vertex_count = 0;
  std::vector<uint32_t> faces;              // 3 vertex ids per triangle, shared by all frames
  std::vector<std::vector<float>> frames;   // per frame: vertex_count * 3 floats (x, y, z)
  double frame_rate = 30.0;                 // frames per second
};

// Reads one triangle mesh. Polygons are triangulated by OpenMesh; errors name the file.
bool read_mesh(const std::string& path, std::vector<float>* xyz, std::vector<uint32_t>* faces,
               std::string* error);

// Writes one mesh; the format follows the extension (.obj, .ply, .off). Written to a
// temporary name and renamed, so a failure leaves no partial file.
bool write_mesh(const std::string& path, const float* xyz, uint32_t vertex_count,
                const std::vector<uint32_t>& faces, std::string* error);

// Reads every .obj/.ply/.off file of `dir` in frame-number order (encoder/io/frame_order.h). All frames must have the same
// vertex count and face list, and finite coordinates.
bool read_frame_folder(const std::string& dir, Animation* anim, std::string* error);

// Writes DIR/frame_00000.EXT, frame_00001.EXT, ... (EXT = "obj" or "ply"); creates DIR.
bool write_frame_folder(const std::string& dir, const Animation& anim, const std::string& ext,
                        std::string* error);

// Checks an animation in memory: non-empty, consistent counts, indices in range, finite.
bool validate_animation(const Animation& anim, std::string* error);

}  // namespace dcurve
