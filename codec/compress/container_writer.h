// Writing the .dcrv container (format_spec/dcrv.md describes every byte;
// codec/decompress/container_reader.h reads it back).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "codec/common/container_format.h"
#include "codec/common/model.h"

namespace dcurve {

struct WriteOptions {
  // Store faces; engines that already hold the mesh can drop them. The residual layer
  // predicts from whatever neighbours the file carries, so a model written without faces
  // must have had its residual coded with model.faces empty (encode_animation does this).
  bool connectivity = true;
  // A reader always gets model.faces back exactly. Smallest picks whichever FACE layout
  // stores smallest: Exact, Compact, or Traversal when model.faces is already in
  // traversal_order (codec/compress/faces_encoder.h). Each other value forces that layout
  // when it can hold model.faces (Traversal: a list in traversal order; Compact: within its
  // triangle-per-byte bound) and falls back to Exact otherwise: for test vectors and
  // measurements.
  enum class FaceLayout { Smallest, Exact, Traversal, Compact };
  FaceLayout face_layout = FaceLayout::Smallest;
  int zstd_level = 19;       // 1..22
};

// Payload bytes the FACE section of write_container(model, options) would store for
// model.faces = faces (section header not included): lets an encoder compare face orders.
uint64_t face_payload_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options = {});
// The whole FACE section, header included, as write_container would store it.
uint64_t face_section_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options = {});

// Serializes `model` (which must pass validate_model). The RESI section is written only when
// model.residual.step > 0; FACE only when options.connectivity and faces are present.
// sections: what each section takes in the file, as read_container would report it.
std::vector<uint8_t> write_container(const Model& model, const WriteOptions& options = {},
                                     std::vector<SectionInfo>* sections = nullptr);

// Bytes one SEGS motion record of `m` takes (dcrv.md section 8): 1 for a Zero motion; the
// coefficients must already be quantized (quantize_coefficients).
size_t motion_record_size(const CurveMotion& m);

}  // namespace dcurve
