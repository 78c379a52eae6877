// dcurve runtime decoder, C++ API. Open a .dcrv once, then evaluate the mesh at any t.
// Depends on the C++17 standard library and zstd only.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

namespace dcurve {

class Decoder {
 public:
  // Opens a file held in memory (the bytes are copied as needed; the caller may free them
  // after the call). Returns nullptr and sets *error on any malformed or truncated input.
  static std::unique_ptr<Decoder> open_memory(const void* data, size_t size, std::string* error);
  // Reads and opens a file. Errors name the path.
  static std::unique_ptr<Decoder> open_file(const std::string& path, std::string* error);
  ~Decoder();

  uint32_t vertex_count() const;
  uint32_t frame_count() const;          // input frames; frame f sits at t = f / (frame_count - 1)
  uint32_t face_count() const;           // 0 when the file omits connectivity
  const uint32_t* faces() const;         // 3 * face_count vertex ids, or nullptr
  double frame_rate() const;             // frames per second of the input
  double tolerance() const;              // promised max error, fraction of the rest-pose diagonal
  double rest_diagonal() const;          // L, model units

  // Writes vertex_count * 3 floats (x, y, z per vertex, input vertex order) for time t in
  // [0, 1] (clamped). At t = f / (frame_count - 1) the result is input frame f within the
  // tolerance. No allocation; safe to call from several threads at once.
  void evaluate(double t, float* xyz_out) const;
  // Same for input frame f in [0, frame_count) (clamped): exact reconstruction of that frame.
  void evaluate_frame(uint32_t f, float* xyz_out) const;
  // Area-weighted unit vertex normals of positions `xyz` (vertex_count * 3 floats) into
  // `normals_out` (same size). Needs connectivity; returns false when the file has none.
  bool compute_normals(const float* xyz, float* normals_out) const;

  struct Impl;

 private:
  explicit Decoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace dcurve
