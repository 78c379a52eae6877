// Where decoded or simulated frames go, chosen by the output path (cli/output_path): one
// mesh (.obj, .ply, .off), a glTF file (.glb, .gltf), a point cache (.pc2, .mdd) or a folder
// of frames. Frames arrive one at a time and are streamed out (one mesh keeps its one frame).
// Every kind is written through encoder/io's OutputFile or OutputFolder: nothing appears at
// the output path until finish() succeeds, and what was there stays until then.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cli/output_path.h"
#include "encoder/io/gltf_writer.h"
#include "encoder/io/mesh_writer.h"

namespace dcurve::cli {

struct OutputSpec {
  std::string path;
  OutputKind kind = OutputKind::Folder;
  std::string folder_format = "obj";  // the frames' format in a folder: obj or ply
  bool force = false;                 // replace an existing file, or a folder's frames
  uint32_t vertex_count = 0, frame_count = 0;
  std::vector<uint32_t> faces;
  double frame_rate = 30;
  double start_time = 0;              // seconds of the first frame (PC2 start frame, MDD and glTF times)
  GltfScene gltf;                     // a glTF output's static attributes, placement and normals
  ObjRender obj;                      // an OBJ output's UVs, groups and material library
  std::vector<std::string> inputs;    // files the command reads: never the output
};

class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // Frame `index` of frame_count, in order; `normals` (same size, or null) where the output
  // asked for them (OutputSpec::gltf.normals).
  virtual bool add(uint32_t index, const float* xyz, const float* normals, std::string* error) = 0;
  // Moves the complete output into place.
  virtual bool finish(std::string* error) = 0;
};

// Checks the output (the overwrite rule, a glTF output not too large) and opens it, before
// any frame is made; nullptr and a message if not.
std::unique_ptr<FrameSink> open_output(const OutputSpec& spec, std::string* error);

}  // namespace dcurve::cli
