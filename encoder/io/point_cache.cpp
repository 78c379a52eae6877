#include "encoder/io/point_cache.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "codec/common/error.h"
#include "encoder/io/files.h"
#include "encoder/io/frame_times.h"
#include "encoder/io/output_file.h"

namespace dcurve {
namespace {

constexpr char kPc2Signature[12] = "POINTCACHE2";
constexpr size_t kPc2HeaderBytes = 32;

// Byte order is explicit (PC2 little-endian, MDD big-endian) so the files are the same on
// any host.
uint32_t load_u32(const uint8_t* p, bool big) {
  return big ? uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | p[3]
             : uint32_t(p[3]) << 24 | uint32_t(p[2]) << 16 | uint32_t(p[1]) << 8 | p[0];
}
float load_f32(const uint8_t* p, bool big) {
  uint32_t u = load_u32(p, big);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}
void store_u32(std::vector<uint8_t>* out, uint32_t u, bool big) {
  for (int i = 0; i < 4; ++i) out->push_back(uint8_t(u >> (big ? 24 - 8 * i : 8 * i)));
}
void store_f32(std::vector<uint8_t>* out, float f, bool big) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  store_u32(out, u, big);
}

// Reads frame_count frames of positions starting at `data`; the caller checked the size.
bool read_positions(const std::string& path, const uint8_t* data, bool big, Animation* anim, std::string* error) {
  const size_t values = size_t(anim->vertex_count) * 3;
  for (auto& frame : anim->frames) {
    frame.resize(values);
    for (size_t i = 0; i < values; ++i, data += 4) {
      frame[i] = load_f32(data, big);
      if (!std::isfinite(frame[i]))
        return fail(error, path + ": frame " + std::to_string(&frame - anim->frames.data()) + ", vertex " +
                               std::to_string(i / 3) + ": value is not a finite number");
    }
  }
  return true;
}

// Checks that a header's counts account for exactly the file's bytes.
bool check_size(const std::string& path, size_t header, uint64_t frames, uint64_t vertices, size_t file_bytes,
                std::string* error) {
  if (vertices == 0) return fail(error, path + ": the header says 0 vertices");
  if (frames == 0) return fail(error, path + ": the header says 0 frames");
  // Compared by division: frames x vertices x 12 can wrap around 64 bits.
  const uint64_t frame_bytes = vertices * 12;
  const bool fits = file_bytes >= header && (file_bytes - header) % frame_bytes == 0 &&
                    (file_bytes - header) / frame_bytes == frames;
  if (!fits) {
    const long double expected = header + (long double)frames * frame_bytes;
    char needed[64];
    std::snprintf(needed, sizeof needed, "%.0Lf", expected);
    return fail(error, path + ": " + std::to_string(file_bytes) + " bytes, but a header of " + std::to_string(frames) +
                           " frames x " + std::to_string(vertices) + " vertices needs " + needed +
                           (expected > file_bytes ? " (truncated file?)" : " (trailing bytes)"));
  }
  return true;
}

bool read_pc2(const std::string& path, const std::vector<uint8_t>& b, Animation* anim, PointCacheInfo* info,
              std::string* error) {
  if (b.size() < kPc2HeaderBytes || std::memcmp(b.data(), kPc2Signature, 12) != 0)
    return fail(error, path + ": not a PC2 file (no POINTCACHE2 header)");
  const uint32_t vertices = load_u32(&b[16], false), frames = load_u32(&b[28], false);
  if (!check_size(path, kPc2HeaderBytes, frames, vertices, b.size(), error)) return false;
  info->start = load_f32(&b[20], false);
  info->frame_rate = 0;  // PC2 stores a sample step in frames, not a rate
  anim->vertex_count = vertices;
  anim->frames.resize(frames);
  return read_positions(path, &b[kPc2HeaderBytes], false, anim, error);
}

bool read_mdd(const std::string& path, const std::vector<uint8_t>& b, Animation* anim, PointCacheInfo* info,
              std::string* error) {
  if (b.size() < 8) return fail(error, path + ": too short for an MDD header");
  const uint64_t frames = load_u32(&b[0], true), vertices = load_u32(&b[4], true);
  if (!check_size(path, 8 + 4 * frames, frames, vertices, b.size(), error)) return false;
  std::vector<double> times(frames);
  for (size_t f = 0; f < frames; ++f) times[f] = load_f32(&b[8 + 4 * f], true);
  info->start = times[0];
  info->frame_rate = 0;
  if (!frame_rate_from_times(times, path + ": the MDD frame times", &info->frame_rate, error)) return false;
  anim->vertex_count = uint32_t(vertices);
  anim->frames.resize(frames);
  return read_positions(path, &b[8 + 4 * frames], true, anim, error);
}

}  // namespace

bool point_cache_kind(const std::string& path, PointCacheKind* kind) {
  const std::string ext = lowercase_extension(path);
  if (ext == ".pc2") *kind = PointCacheKind::Pc2;
  else if (ext == ".mdd") *kind = PointCacheKind::Mdd;
  else return false;
  return true;
}

bool read_point_cache(const std::string& path, Animation* anim, PointCacheInfo* info, std::string* error,
                      uint64_t max_memory) {
  PointCacheKind kind;
  if (!point_cache_kind(path, &kind)) return fail(error, path + ": not a .pc2 or .mdd file");
  std::vector<uint8_t> bytes;
  // The frames take about the file's size again: both must fit.
  if (!read_file(path, &bytes, error, max_memory / 2)) return false;
  *anim = Animation{};
  *info = PointCacheInfo{};
  const bool ok = kind == PointCacheKind::Pc2 ? read_pc2(path, bytes, anim, info, error)
                                              : read_mdd(path, bytes, anim, info, error);
  if (!ok) return false;
  info->vertex_count = anim->vertex_count;
  info->frame_count = uint32_t(anim->frames.size());
  if (info->frame_rate > 0) anim->frame_rate = info->frame_rate;
  return true;
}

bool PointCacheWriter::write_header(uint32_t frame_count, double frame_rate, double start_time, std::string* error) {
  buffer_.clear();
  if (kind_ == PointCacheKind::Pc2) {
    buffer_.assign(kPc2Signature, kPc2Signature + 12);
    store_u32(&buffer_, 1, false);  // file version
    store_u32(&buffer_, vertex_count_, false);
    store_f32(&buffer_, float(start_time * frame_rate), false);  // start frame
    store_f32(&buffer_, 1.0f, false);  // sample step: every frame
    store_u32(&buffer_, frame_count, false);
  } else {
    store_u32(&buffer_, frame_count, true);
    store_u32(&buffer_, vertex_count_, true);
    for (uint32_t f = 0; f < frame_count; ++f) store_f32(&buffer_, float(start_time + f / frame_rate), true);
  }
  return out_->write(buffer_.data(), buffer_.size(), error);
}

bool PointCacheWriter::write_frame(const float* xyz, std::string* error) {
  buffer_.clear();
  const bool big = kind_ == PointCacheKind::Mdd;
  for (size_t i = 0; i < size_t(vertex_count_) * 3; ++i) store_f32(&buffer_, xyz[i], big);
  return out_->write(buffer_.data(), buffer_.size(), error);
}

}  // namespace dcurve
