// dcurve runtime decoder, C++ API. Open a .dcrv once, then evaluate the mesh at any t.
// Depends on the C++17 standard library and zstd only.
//
// Memory: an open Decoder holds the file's shared sections (faces, curves, models), the
// chunk index and either the compressed chunks (open_memory) or nothing of them
// (open_file: chunks are read from the file when a frame needs them). Decoded frames live
// in a Cursor: one chunk and the frame before it (and, under a cubic in-between rule,
// copies of the up to six frames around the time evaluated), so memory does not grow with
// the clip. A format 4 file (the fast profile) needs no chunk: a Cursor holds the last three
// decoded frames, two frames of Model prediction and one of 64-bit spatial corrections, and
// reaches a frame by decoding its chunk's frames up to it.
//
// Thread safety: a Decoder is immutable after opening; any number of threads may share
// it. A Cursor belongs to one thread at a time (make one per thread). The Decoder's own
// evaluate calls use an internal cursor behind a mutex: safe from many threads, one at a
// time.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "dcurve.h"

namespace dcurve {

// Why a call failed (the C ABI's DCURVE_ERROR_* codes).
enum class Status : int {
  Ok = DCURVE_OK,
  Malformed = DCURVE_ERROR_MALFORMED,           // not a valid .dcrv, or a version this build does not read
  InvalidArgument = DCURVE_ERROR_INVALID_ARGUMENT,
  Io = DCURVE_ERROR_IO,                         // the file cannot be opened or read
  CorruptChunk = DCURVE_ERROR_CORRUPT_CHUNK,    // a chunk fails its checksum or does not decode
  OutOfMemory = DCURVE_ERROR_OUT_OF_MEMORY,
  Internal = DCURVE_ERROR_INTERNAL,
};

// The outcome of a call: Ok, or a status and a message naming the problem.
struct Error {
  Status status = Status::Ok;
  std::string message;
};

// How evaluate fills the time between two stored frames (format_spec/dcrv.md section 13):
// linear blending, or a cubic in time through the neighbouring frames (no bytes in the
// file). A file records the rule its encoder found best (format 3.2; older files: Linear);
// a caller may override it. Stored frames evaluate the same under every rule.
enum class Interpolation : int {
  Linear = DCURVE_INTERPOLATION_LINEAR,
  CatmullRom = DCURVE_INTERPOLATION_CATMULL_ROM,
  Hermite4 = DCURVE_INTERPOLATION_HERMITE4,
};

// Static attributes of render vertices (format 3.3 / 4.1).
enum class Attribute : int {
  TexCoord0 = DCURVE_ATTRIBUTE_TEXCOORD_0,
  TexCoord1 = DCURVE_ATTRIBUTE_TEXCOORD_1,
  Color0 = DCURVE_ATTRIBUTE_COLOR_0,
  Normal = DCURVE_ATTRIBUTE_NORMAL,
};

// Triangles drawn with one material: faces [first_face, first_face + face_count) of
// Decoder::group_faces(). material indexes the "materials" of materials_json(), -1 for none.
struct Group {
  uint32_t first_face = 0, face_count = 0;
  int material = -1;
  std::string name;
};

class Cursor;

class Decoder {
 public:
  // Opens a file held in memory; the compressed chunks are copied, so the caller may free
  // `data` after the call. Returns nullptr and sets *error on malformed or truncated input.
  static std::unique_ptr<Decoder> open_memory(const void* data, size_t size, std::string* error,
                                              Status* status = nullptr);
  // Opens a file by path: reads everything but the chunks, which are read (and checked)
  // when a frame needs them; a file truncated or rewritten after opening is detected then.
  // Errors name the path.
  static std::unique_ptr<Decoder> open_file(const std::string& path, std::string* error, Status* status = nullptr);
  ~Decoder();

  uint32_t vertex_count() const;
  uint32_t frame_count() const;          // input frames; frame f sits at t = f / (frame_count - 1)
  uint32_t face_count() const;           // 0 when the file omits connectivity
  const uint32_t* faces() const;         // 3 * face_count vertex ids, or nullptr
  double frame_rate() const;             // frames per second of the input (0: unknown)
  double tolerance() const;              // promised max error, fraction of the rest-pose diagonal
  double rest_diagonal() const;          // L, model units
  uint32_t chunk_frames() const;         // frames per chunk (0 when the file has no residual layer)
  uint32_t chunk_count() const;
  Interpolation interpolation() const;   // the rule the file records

  // The rule the Decoder's own evaluate uses from now on (the file's until set); cursors
  // made later start with the file's rule. Thread-safe like evaluate.
  void set_interpolation(Interpolation rule);

  // Writes vertex_count * 3 floats (x, y, z per vertex, input vertex order) for time t in
  // [0, 1] (clamped; NaN reads as 0). At t = f / (frame_count - 1) the result is input frame
  // f within the tolerance. Decodes the chunks it needs into the internal cursor. False
  // (output unspecified) when a chunk cannot be read or decoded; the decoder stays usable.
  bool evaluate(double t, float* xyz_out, Error* error = nullptr) const;
  // Same for input frame f in [0, frame_count) (clamped).
  bool evaluate_frame(uint32_t f, float* xyz_out, Error* error = nullptr) const;
  // Area-weighted unit vertex normals of positions `xyz` (vertex_count * 3 floats) into
  // `normals_out` (same size). Needs connectivity; returns false when the file has none.
  bool compute_normals(const float* xyz, float* normals_out) const;

  // Render vertices: what a game draws (dcurve.h says more). Without REND (files before
  // 3.3, or inputs without seams or attributes) they are the vertices: render_source and
  // render_faces are nullptr and render_vertex_count() == vertex_count().
  uint32_t render_vertex_count() const;
  const uint32_t* render_source() const;  // per render vertex, its vertex
  const uint32_t* render_faces() const;   // 3 * face_count render ids, the faces' order
  // render_vertex_count * attribute_components(a) floats, or nullptr when the file has none.
  uint32_t attribute_components(Attribute a) const;
  const float* attribute(Attribute a) const;
  const float* uvs() const { return attribute(Attribute::TexCoord0); }
  const float* colors() const { return attribute(Attribute::Color0); }
  // Render vertex positions (render_vertex_count * 3) from vertex positions `xyz`.
  void render_positions(const float* xyz, float* render_xyz_out) const;
  // Unit normals per render vertex: copies of a vertex share one (smooth across UV seams)
  // unless the input's normals differ between them. Needs connectivity.
  bool compute_render_normals(const float* xyz, float* normals_out) const;
  // Face groups (one per material of the input; none for a file without them) and the render
  // triangles ordered by group, each group's in the faces' order.
  uint32_t group_count() const;
  Group group(uint32_t i) const;
  const std::string& group_name(uint32_t i) const;  // the decoder's own copy ("" past the last)
  const uint32_t* group_faces() const;  // 3 * face_count render ids, or nullptr without groups
  // The groups' materials as the input's glTF wrote them: a JSON object with "materials",
  // "textures", "samplers", "images" (empty without MATL); image i's bytes and media type.
  const std::string& materials_json() const;
  uint32_t image_count() const;
  const uint8_t* image(uint32_t i, size_t* size) const;
  const std::string& image_mime_type(uint32_t i) const;
  // Placement (PLAC): frame 0's time in seconds in the input's timeline (0 unknown), the
  // input node's world transform (column-major; false and identity when the file has none),
  // the input's mesh and node names.
  double start_time() const;
  bool world_matrix(double matrix_out[16]) const;
  const std::string& mesh_name() const;
  const std::string& node_name() const;
  // A cursor of its own for one thread (sequential playback decodes each chunk once).
  // The cursor refers to this decoder, which must outlive it.
  std::unique_ptr<Cursor> make_cursor() const;

  // Bytes this decoder holds now: shared tables, the compressed chunks it keeps and its
  // internal cursor's window (not the cursors made by make_cursor).
  size_t memory_bytes() const;

  struct Impl;

 private:
  explicit Decoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

// A window of decoded chunks and the buffers decoding needs: evaluates frames of one
// Decoder. Not thread-safe: one cursor per thread.
class Cursor {
 public:
  ~Cursor();
  bool evaluate(double t, float* xyz_out, Error* error = nullptr);
  bool evaluate_frame(uint32_t f, float* xyz_out, Error* error = nullptr);
  // The rule this cursor's evaluate uses from now on (the file's until set).
  void set_interpolation(Interpolation rule);
  // Bytes the cursor holds: its window of decoded chunks and decoding buffers.
  size_t memory_bytes() const;

  struct State;

 private:
  friend class Decoder;
  explicit Cursor(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

// The library's version, DCURVE_VERSION as a number.
uint32_t version();

}  // namespace dcurve
