// What the writer and the reader of the .dcrv container share (format_spec/dcrv.md describes
// every byte): the version, the file header, the section tags and flags, what a section
// takes, the coefficient range. codec/compress/container_writer.h writes the container,
// codec/decompress/container_reader.h reads it.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dcurve {

// Version written by write_container. Readers accept any minor of their major: a newer minor
// adds optional sections, hint flags, or required feature flags an older reader refuses.
constexpr uint16_t kFormatVersionMajor = 3;
constexpr uint16_t kFormatVersionMinor = 2;
// Format 4.0: 3.2 whose residual layer (RESI) is a fast payload (residual payload version
// 5, codec/common/fast_residual.h). The writer writes it exactly for such files, so files
// of the small profile stay 3.2; a reader reads both majors.
constexpr uint16_t kFastFormatVersionMajor = 4;
constexpr uint16_t kFastFormatVersionMinor = 0;
// Minor 3 (format 3.3) and 1 (4.1): optional REND and PLAC sections (render vertices and
// their attributes; placement, start time, names). Written exactly for files that hold them,
// so other files keep their version; older readers skip both and decode the same positions.
constexpr uint16_t kRenderFormatVersionMinor = 3;
constexpr uint16_t kFastRenderFormatVersionMinor = 1;
// Minor 2 of format 4 (4.2; it may hold REND and PLAC too): LRNK's differences packed
// through zstd, a bit 4.0 and 4.1 readers refuse. Written exactly for format 4 files with LRNK.
constexpr uint16_t kFastPackedFormatVersionMinor = 2;
// Minor 3 of format 4 (4.3): the LRNK basis payload's kinds may carry the Fit flag
// (residual.md section 10.7), which 4.2 readers refuse. Written for every format 4 file with
// LRNK (4.2 is never written now).
constexpr uint16_t kFastFitBasisFormatVersionMinor = 3;
// Required feature (file_flags bit 0, since 3.1): residual payloads may be of version 4 (zero
// block flags), which a 3.0 reader cannot decode. The writer always sets it.
constexpr uint32_t kFileFlagZeroBlocks = 1u;
// Required feature (file_flags bit 1, since 3.2): META ends with the in-between rule byte
// (Metadata::inbetween). Set exactly when the rule is not Linear, so a 3.1 reader refuses
// only files it would evaluate differently between frames.
constexpr uint32_t kFileFlagInbetween = 2u;

// One section as a file stores it: what the reader finds and the writer reports.
struct SectionInfo {
  std::string tag;        // four ASCII characters
  bool required = false;
  bool compressed = false;
  uint64_t offset = 0;        // file offset of the section header
  uint64_t header_bytes = 0;  // the section header's size: 28, or 10..26 when compact
  uint64_t stored_bytes = 0;  // bytes in the file after the section header
  uint64_t raw_bytes = 0;     // bytes after decompression
  int face_layout = -1;       // FACE only: 0 exact, 1 traversal, 2 compact (codec/common/faces.h)
};

// Bytes the FACE section takes in the file, its section header included (0 without one):
// what dropping connectivity would save.
inline uint64_t connectivity_bytes(const std::vector<SectionInfo>& sections) {
  uint64_t bytes = 0;
  for (const SectionInfo& s : sections)
    if (s.tag == "FACE") bytes += s.stored_bytes + s.header_bytes;
  return bytes;
}

// The fixed 28-byte file header.
struct ContainerHeader {
  uint16_t version_major = 0, version_minor = 0;
  uint32_t flags = 0;
  uint32_t section_count = 0;
  uint64_t head_bytes = 0;  // header and sections: where the chunk data begins
};
constexpr size_t kContainerHeaderBytes = 28;

// Range of CurveMotion::coeff_exponent a file may store, and the bound on the stored
// integers: |k| < 2^kCoeffIntegerBits, so k * 2^exponent is exact in binary32.
constexpr int kCoeffExponentMin = -100, kCoeffExponentMax = 40, kCoeffIntegerBits = 24;

// The byte layout both sides spell the same way.
namespace container_format {

constexpr char kMagic[4] = {'D', 'C', 'R', 'V'};
constexpr size_t kHeaderBytes = kContainerHeaderBytes;
constexpr uint16_t kSectionRequired = 1;
constexpr uint16_t kSectionZstd = 2;

inline uint32_t fourcc(const char* s) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}

const uint32_t kMeta = fourcc("META");
const uint32_t kFaces = fourcc("FACE");
const uint32_t kCurves = fourcc("CURV");
const uint32_t kSegments = fourcc("SEGS");
const uint32_t kLowRank = fourcc("LRNK");
const uint32_t kResidual = fourcc("RESI");
const uint32_t kRender = fourcc("REND");
const uint32_t kPlacement = fourcc("PLAC");
const uint32_t kMaterials = fourcc("MATL");

// A tag as four printable characters ('?' for others).
inline std::string tag_name(uint32_t t) {
  std::string s(4, '?');
  for (int i = 0; i < 4; ++i) {
    const char c = char((t >> (8 * i)) & 0xff);
    s[size_t(i)] = (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

// Curve parameters u as 16-bit fixed point (CURV section).
inline uint16_t u_to_fixed(float u) { return uint16_t(std::lround(std::clamp(u, 0.f, 1.f) * 65535.f)); }
inline float u_from_fixed(uint16_t q) { return float(q) / 65535.f; }

}  // namespace container_format
}  // namespace dcurve
