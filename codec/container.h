// Reading and writing the .dcrv container (format_spec/dcrv.md describes every byte).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "codec/model.h"

namespace dcurve {

// Version written by write_container. Readers accept any minor of their major: a newer minor
// only adds optional sections and hint flags.
constexpr uint16_t kFormatVersionMajor = 3;
constexpr uint16_t kFormatVersionMinor = 0;

// Values (floats or grid values) a decoder may build for a file of `file_bytes` bytes:
// max(2^23, 8192 * file_bytes), the bound that keeps a small hostile file from asking for
// gigabytes (format_spec/dcrv.md section 15). read_container rejects V * max(F, 1) * 3
// above it.
uint64_t decoder_value_budget(size_t file_bytes);

struct WriteOptions {
  // Store faces; engines that already hold the mesh can drop them. The residual layer
  // predicts from whatever neighbours the file carries, so a model written without faces
  // must have had its residual coded with model.faces empty (encode_animation does this).
  bool connectivity = true;
  // A reader always gets model.faces back exactly. Smallest picks whichever FACE layout
  // stores smallest: Exact, Compact, or Traversal when model.faces is already in
  // traversal_order (codec/faces.h). Each other value forces that layout when it can hold
  // model.faces (Traversal: a list in traversal order; Compact: within its triangle-per-byte
  // bound) and falls back to Exact otherwise: for test vectors and measurements.
  enum class FaceLayout { Smallest, Exact, Traversal, Compact };
  FaceLayout face_layout = FaceLayout::Smallest;
  int zstd_level = 19;       // 1..22
};

// One section as found in a file, for `dcurve info`.
struct SectionInfo {
  std::string tag;        // four ASCII characters
  bool required = false;
  bool compressed = false;
  uint64_t offset = 0;        // file offset of the section header
  uint64_t header_bytes = 0;  // the section header's size: 28, or 10..26 when compact
  uint64_t stored_bytes = 0;  // bytes in the file after the section header
  uint64_t raw_bytes = 0;     // bytes after decompression
  int face_layout = -1;       // FACE only: 0 exact, 1 traversal, 2 compact (codec/faces.h)
};

// The fixed 28-byte file header.
struct ContainerHeader {
  uint16_t version_major = 0, version_minor = 0;
  uint32_t flags = 0;
  uint32_t section_count = 0;
  uint64_t head_bytes = 0;  // header and sections: where the chunk data begins
};
constexpr size_t kContainerHeaderBytes = 28;

// Bytes the FACE section takes in the file, its section header included (0 without one):
// what dropping connectivity would save.
uint64_t connectivity_bytes(const std::vector<SectionInfo>& sections);

// Payload bytes the FACE section of write_container(model, options) would store for
// model.faces = faces (section header not included): lets an encoder compare face orders.
uint64_t face_payload_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options = {});

// Reads the header fields without checking anything else; false when size < 24 or the
// magic is wrong. For tools that describe a file that read_container already accepted.
bool peek_header(const uint8_t* data, size_t size, ContainerHeader* header);

// Serializes `model` (which must pass validate_model). The RESI section is written only when
// model.residual.step > 0; FACE only when options.connectivity and faces are present.
std::vector<uint8_t> write_container(const Model& model, const WriteOptions& options = {});

// The value a reader gets back for curve parameter u (stored as 16-bit fixed point): an
// encoder fits against these so its closed loop sees what the decoder sees. u in [0, 1].
float quantize_curve_u(float u);

// Range of CurveMotion::coeff_exponent a file may store, and the bound on the stored
// integers: |k| < 2^kCoeffIntegerBits, so k * 2^exponent is exact in binary32.
constexpr int kCoeffExponentMin = -100, kCoeffExponentMax = 40, kCoeffIntegerBits = 24;

// Rounds every coefficient of `m` to the nearest multiple of 2^exponent (to nearest, ties
// away from zero) and stores the exponent, which is first raised as far as the largest
// coefficient needs for |k| < 2^24 and clamped to [kCoeffExponentMin, kCoeffExponentMax].
// The result is exactly what a reader gets back. Returns the exponent used.
int quantize_coefficients(CurveMotion* m, int exponent);

// Bytes one SEGS motion record of `m` takes (dcrv.md section 8): 1 for a Zero motion; the
// coefficients must already be quantized (quantize_coefficients).
size_t motion_record_size(const CurveMotion& m);

// Parses and validates a whole file. On failure returns false and a message naming the
// problem; never reads outside [data, data + size) and bounds every allocation by `size`.
// model->residual.payload receives the chunk index and the chunks.
bool read_container(const uint8_t* data, size_t size, Model* model, std::string* error,
                    std::vector<SectionInfo>* sections = nullptr);

// The file header alone (kContainerHeaderBytes of `data`), checked: magic, CRC, version,
// flags, and head_bytes within [kContainerHeaderBytes, file_bytes]. What a reader that
// loads chunks on demand reads first, to learn how much more it needs before any chunk.
bool read_container_header(const uint8_t* data, size_t size, uint64_t file_bytes, ContainerHeader* header,
                           std::string* error);

// Parses and validates the head of a file of file_bytes bytes (head: its first
// header.head_bytes bytes, as read_container_header gave them): everything but the chunk
// data, which it checks only by size against the chunk index. model->residual.payload
// receives the index alone and residual.external_bytes the chunk data's size, which
// starts at file offset head_bytes.
bool read_container_head(const uint8_t* head, size_t head_size, uint64_t file_bytes, Model* model,
                         std::string* error, std::vector<SectionInfo>* sections = nullptr);

}  // namespace dcurve
