// Point caches in and out: PC2 (Blender, 3ds Max, Houdini; little-endian, a start frame and
// a sample step) and MDD (LightWave, Blender, Houdini; big-endian, one time per frame).
// Both hold positions only, so reading takes the faces from a separate rest mesh.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "encoder/io/frames.h"
#include "encoder/io/read_limits.h"
#include "encoder/io/output_file.h"

namespace dcurve {

enum class PointCacheKind { Pc2, Mdd };

// What a cache's header says besides the positions.
struct PointCacheInfo {
  uint32_t vertex_count = 0, frame_count = 0;
  double start = 0;        // PC2: start frame; MDD: time of the first frame, seconds
  double frame_rate = 0;   // MDD: from its evenly spaced frame times (0 when it has one frame); PC2: 0
};

// ".pc2" -> Pc2, ".mdd" -> Mdd (any case); false for other extensions.
bool point_cache_kind(const std::string& path, PointCacheKind* kind);

// Reads every frame of a PC2 or MDD file into anim->frames (faces left empty). Errors name the
// file: not a regular file (a FIFO, a device, a link to one), larger than half of
// `max_memory` (the frames take as much again), a header that does not match the file's size,
// a non-finite value, MDD frame times that are not finite, strictly increasing and evenly
// spaced (encoder/io/frame_times.h).
bool read_point_cache(const std::string& path, Animation* anim, PointCacheInfo* info, std::string* error,
                      uint64_t max_memory = default_max_memory());

// Writes a cache one frame at a time into an open OutputFile (the caller commits it). The
// header needs the frame count up front; start_time (seconds of the first frame) becomes
// PC2's start frame at `frame_rate`, or MDD's first time.
class PointCacheWriter {
 public:
  PointCacheWriter(PointCacheKind kind, OutputFile* out, uint32_t vertex_count) : kind_(kind), out_(out), vertex_count_(vertex_count) {}
  bool write_header(uint32_t frame_count, double frame_rate, double start_time, std::string* error);
  bool write_frame(const float* xyz, std::string* error);

 private:
  PointCacheKind kind_;
  OutputFile* out_;
  uint32_t vertex_count_;
  std::vector<uint8_t> buffer_;
};

}  // namespace dcurve
