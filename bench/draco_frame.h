// One mesh frame through libdraco and back: edgebreaker connectivity (compression level 10,
// i.e. encoding speed 0), quantized positions, decoded by libdraco and matched back to the
// input vertex order.
//
// Draco reorders vertices (edgebreaker traversal order) and may split non-manifold ones, so
// decoded points are matched back to input vertices. A generic index attribute would change
// the traversal itself (measured: the decoded order then differs), so one calibration file
// instead spells each vertex's index in its positions; the measured files carry the real
// positions alone. The decoded order depends on connectivity only, which every decode checks:
// its face list must equal the calibration's, point for point, or the decode fails.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve::bench {

class DracoFrameCodec {
 public:
  // Learns the decoded point order for the triangles `faces` (3 ids per triangle) over
  // `vertex_count` (at most 2^20) vertices. Fails when Draco cannot encode the mesh or drops
  // a vertex (e.g. one used by no triangle).
  bool init(uint32_t vertex_count, const std::vector<uint32_t>& faces, std::string* error);

  // A self-contained Draco file of the mesh with positions `xyz` (vertex_count * 3 floats)
  // quantized to `bits` in [1, 30] over the frame's own bounding box.
  bool encode(const float* xyz, int bits, std::vector<char>* file, std::string* error) const;

  // Decodes `file` with libdraco into `xyz` (vertex_count * 3 floats, input vertex order).
  // `verify` checks the decoded faces against the calibration (skip it only to time a file
  // already verified, so the timing is libdraco's).
  bool decode(const std::vector<char>& file, std::vector<float>* xyz, std::string* error, bool verify = true) const;

  // Bytes of a Draco file holding the connectivity and constant positions: the cost of the
  // edgebreaker-coded connectivity plus the file header, charged by baselines that code
  // connectivity once.
  uint64_t connectivity_bytes() const { return connectivity_bytes_; }

  uint32_t vertex_count() const { return vertex_count_; }

 private:
  uint32_t vertex_count_ = 0;
  std::vector<uint32_t> faces_;
  std::vector<uint32_t> point_to_vertex_;  // decoded point id -> input vertex id
  std::vector<uint32_t> decoded_faces_;    // the calibration decode's faces, in point ids
  uint64_t connectivity_bytes_ = 0;
};

}  // namespace dcurve::bench
