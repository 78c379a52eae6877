// Animated meshes in and out: a folder of OBJ/PLY/OFF frames with fixed connectivity,
// read through OpenMesh's readers. Vertex order is never changed: vertex i read is the file's
// vertex i, and a file the reader would alter (a skipped record, an unusable face) is refused.
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "encoder/animation.h"

namespace dcurve {

class OutputFolder;
struct ObjCorners;

// Reads one mesh (a regular file; a FIFO or device is refused by name). OBJ is parsed by
// encoder/io/obj_reader.h, which opens no other file; OFF and PLY through OpenMesh's readers.
// Polygons become fans of triangles from their first vertex; non-manifold faces are kept as
// they are. Refused, with the file named: a vertex count or face count that differs from the
// file's own, a face with fewer than 3 vertices, an index out of range or a vertex used twice,
// a coordinate that is not finite or beyond kMaxCoordinate. `corners`, when given, receives an
// OBJ's UVs, normals and materials per corner (empty for OFF and PLY).
bool read_mesh(const std::string& path, std::vector<float>* xyz, std::vector<uint32_t>* faces,
               std::string* error, ObjCorners* corners = nullptr);

// Writes one mesh; the format follows the extension (.obj, .ply, .off; encoder/io/mesh_writer.h).
// Written through an OutputFile, so a failure leaves no partial file; a regular file at `path`
// is replaced only when `replace`. A degenerate triangle is refused (no reader would take the
// file back).
bool write_mesh(const std::string& path, const float* xyz, uint32_t vertex_count,
                const std::vector<uint32_t>& faces, std::string* error, bool replace = true);

// "frame_00012.obj" for index 12 and extension "obj": the names of a folder output.
std::string frame_file_name(size_t index, const std::string& ext);

// Writes frame `index` (frame_file_name, format `ext`: "obj", "ply" or "off") into a folder
// being written.
bool write_folder_frame(OutputFolder* folder, size_t index, const std::string& ext, const float* xyz,
                        uint32_t vertex_count, const std::vector<uint32_t>& faces, std::string* error);

// Folders carry no frame rate: their frame numbers count at this rate, so a folder whose
// numbers step by 2 holds 15 frames per second.
constexpr double kFolderFrameRate = 30.0;

// The .obj/.ply/.off files of `dir` in frame-number order (encoder/io/frame_order.h), paths
// with `dir` in front, and the step between their numbers; false when there are none, the
// order is ambiguous or the step is irregular.
bool list_frame_files(const std::string& dir, std::vector<std::string>* files, std::string* error,
                      long long* frame_step = nullptr);

// Reads every .obj/.ply/.off file of `dir` in frame-number order. All frames must have the same
// vertex count and face list, and finite coordinates. The frame rate is kFolderFrameRate over
// the step between the frame numbers. `progress` gets the fraction of files read.
bool read_frame_folder(const std::string& dir, Animation* anim, std::string* error,
                       const std::function<void(double)>& progress = {});

// Writes DIR/frame_00000.EXT, frame_00001.EXT, ... (EXT = "obj" or "ply") through an
// OutputFolder: DIR is created, or its frames are replaced as a whole.
bool write_frame_folder(const std::string& dir, const Animation& anim, const std::string& ext,
                        std::string* error);

// Coordinates beyond this magnitude are refused by every reader: the codec's float32
// arithmetic (squared distances, bounding boxes) must stay finite.
constexpr float kMaxCoordinate = 1e18f;

// Whether a face (any polygon) names one of its n vertices twice: the one rule for degenerate
// faces. Every reader refuses such a face and every writer refuses to write one.
bool face_repeats_vertex(const uint32_t* ids, size_t n);

// The first triangle of `faces` that repeats a vertex, or SIZE_MAX.
size_t find_degenerate_triangle(const std::vector<uint32_t>& faces);

// Checks an animation in memory: non-empty, consistent counts, indices in range, no
// degenerate triangle (face_repeats_vertex), coordinates finite and within kMaxCoordinate.
bool validate_animation(const Animation& anim, std::string* error);

}  // namespace dcurve
