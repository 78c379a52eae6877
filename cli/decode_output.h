// Where `dcurve decode` puts its frames, chosen by the output path: one mesh (.obj, .ply,
// .off), a glTF file (.glb, .gltf), a point cache (.pc2, .mdd) or a folder of frames. Frames
// arrive one at a time, so a long decode holds one frame (glTF aside: the file holds them
// all). Nothing appears at the output path until finish() succeeds.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace dcurve::cli {

enum class OutputKind { Mesh, Gltf, PointCache, Folder };

// The kind of output a path asks for, from its extension (none: a folder).
OutputKind output_kind(const std::string& path);

// An output file's folder exists and the path is not a folder (checked before work starts).
bool check_output_file(const std::string& path, std::string* error);

struct OutputSpec {
  std::string path;
  std::string folder_format = "obj";  // the frames' format in a folder: obj or ply
  bool force = false;                 // a folder that holds mesh files: replace them
  uint32_t vertex_count = 0, frame_count = 0;
  std::vector<uint32_t> faces;
  double frame_rate = 30;
};

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // Frame `index` of frame_count, in order.
  virtual bool add(uint32_t index, const float* xyz, std::string* error) = 0;
  // Moves the complete output into place.
  virtual bool finish(std::string* error) = 0;
};

// Checks the output (its folder exists, a folder output holds no frames unless forced, a
// glTF output is not too large) before any frame is decoded; nullptr and a message if not.
std::unique_ptr<FrameSink> open_output(const OutputSpec& spec, std::string* error);

}  // namespace dcurve::cli
