#include "codec/compress/container_writer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/common/fast_residual.h"
#include "codec/common/render_format.h"
#include "codec/common/residual.h"
#include "codec/common/residual_index.h"
#include "codec/compress/faces_encoder.h"
#include "codec/compress/low_rank_writer.h"
#include "codec/compress/render_writer.h"
#include "codec/compress/zstd_frame_writer.h"
#include "codec/decompress/container_reader.h"
#include "codec/decompress/zstd_frame.h"

namespace dcurve {
namespace {

using namespace container_format;  // what both sides of the format share

// MATL's level past 64 KiB: its images (PNG, JPEG, KTX2) are mostly compressed already, and
// level 19 spends minutes on megabytes it cannot shrink; level 3 takes what a raw texture
// offers. A smaller MATL (the JSON, small images) keeps the section level: it costs nothing.
constexpr int kImageZstdLevel = 3;
constexpr size_t kImageLevelBytes = size_t(64) << 10;

int section_level(uint32_t tag, size_t raw_bytes, int level) {
  return tag == kMaterials && raw_bytes > kImageLevelBytes ? std::min(level, kImageZstdLevel) : level;
}

// Whether a reader accepts `raw` bytes of section `tag` stored as `stored` (section 15): REND's
// against the value budget of a file of `stored` bytes, which the whole file can only raise.
bool expansion_accepted(uint32_t tag, uint64_t raw, uint64_t stored) {
  return zstd_size_plausible(raw, stored) &&
         (tag != kRender || render_format::kRenderValuesPerByte * raw <= decoder_value_budget(size_t(stored)));
}

// Whether a large section's first MiB shrinks by 1 % or more: a texture that is already PNG or
// JPEG does not, and compressing all of it would hold a second copy of it to throw away.
bool sample_compresses(const std::vector<uint8_t>& raw, int level) {
  constexpr size_t kSample = size_t(1) << 20;
  if (raw.size() <= 4 * kSample) return true;
  const std::vector<uint8_t> head(raw.begin(), raw.begin() + kSample);
  const std::vector<uint8_t> z = zstd_frame(head, level);
  return !z.empty() && z.size() < kSample - kSample / 100;
}

// The zstd frame a section stores when that is smaller than `raw` and within the expansion a
// reader accepts (megabytes of zeros shrink past 4096:1); empty when the raw bytes are stored
// (no copy of them: a section can be a texture of hundreds of megabytes).
std::vector<uint8_t> compressed_form(const std::vector<uint8_t>& raw, int level, uint32_t tag = 0) {
  if (!sample_compresses(raw, level)) return {};
  std::vector<uint8_t> stored = zstd_frame(raw, level);
  if (stored.empty() || stored.size() >= raw.size() || !expansion_accepted(tag, raw.size(), stored.size())) return {};
  return stored;
}

size_t stored_size(const std::vector<uint8_t>& raw, int level) {
  const std::vector<uint8_t> c = compressed_form(raw, level);
  return c.empty() ? raw.size() : c.size();
}

std::vector<uint8_t> face_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options) {
  using Layout = WriteOptions::FaceLayout;
  std::vector<uint8_t> best = encode_faces(faces, FaceOrder::Exact);
  if (options.face_layout == Layout::Exact) return best;
  const int level = options.zstd_level;
  auto consider = [&](std::vector<uint8_t> raw, Layout layout) {
    if (options.face_layout == layout ||
        (options.face_layout == Layout::Smallest && stored_size(raw, level) < stored_size(best, level)))
      best = std::move(raw);
  };
  // Compact reproduces any list exactly (encode_faces falls back to Exact beyond its bound).
  consider(encode_faces(faces, FaceOrder::Compact), Layout::Compact);
  // Traversal may reorder triangles, and other parts of the file (the residual coder's
  // neighbours) were built on model.faces: a candidate only when it gives them back as is.
  std::vector<uint32_t> back;
  std::vector<uint8_t> traversal = encode_faces(faces, FaceOrder::Traversal, &back);
  if (back == faces) consider(std::move(traversal), Layout::Traversal);
  return best;
}

// A section header: tag, u8 flags, varint stored size, varint raw size only when
// compressed, CRC; then the stored bytes. Returns what it wrote (offsets within `out`).
SectionInfo put_section(ByteWriter& out, uint32_t tag, bool required, const std::vector<uint8_t>& raw,
                        int level) {
  const std::vector<uint8_t> zstd = compressed_form(raw, level, tag);
  const bool compressed = !zstd.empty();
  const std::vector<uint8_t>& stored = compressed ? zstd : raw;
  const size_t header_at = out.size();
  out.u32(tag);
  out.u8(uint8_t((required ? kSectionRequired : 0) | (compressed ? kSectionZstd : 0)));
  out.varint(stored.size());
  if (compressed) out.varint(raw.size());
  // The checksum covers the section header too: a flipped tag or flag must not turn a
  // section into an unknown optional one that a reader would silently skip.
  uint32_t crc = crc32c(out.data().data() + header_at, out.size() - header_at);
  out.u32(crc32c(stored.data(), stored.size(), crc));
  const SectionInfo info{tag_name(tag), required, compressed, header_at, out.size() - header_at, stored.size(),
                         raw.size(), tag == kFaces && !raw.empty() ? int(raw[0]) : -1};
  out.bytes(stored.data(), stored.size());
  return info;
}

std::vector<uint8_t> meta_bytes(const Model& m) {
  ByteWriter w;
  w.u32(m.meta.vertex_count);
  w.u32(m.meta.frame_count);
  w.f64(m.meta.frame_rate);
  w.f64(m.meta.tolerance);
  w.f64(m.meta.diag);
  w.str(m.meta.units);
  if (m.meta.inbetween != Inbetween::Linear) w.u8(uint8_t(m.meta.inbetween));
  return std::move(w.data());
}

std::vector<uint8_t> curve_bytes(const Model& m) {
  ByteWriter w;
  const Curves& c = m.curves;
  w.u32(c.curve_count());
  for (uint32_t i = 0; i < c.curve_count(); ++i) w.varint(uint64_t(c.offsets[i + 1] - c.offsets[i]) << 1 | c.closed[i]);
  int64_t prev = 0;
  for (uint32_t v : c.vertices) {
    w.varint(zigzag_encode(int64_t(v) - prev));
    prev = v;
  }
  // u as 16-bit fixed point: 1/65535 of a curve is far below any tolerance the fit sees.
  for (float u : c.u) w.u16(u_to_fixed(u));
  return std::move(w.data());
}

// One SEGS motion record (dcrv.md section 8).
void write_motion(ByteWriter& w, const CurveMotion& cm) {
  w.u8(uint8_t(cm.basis));
  if (cm.basis == Basis::Zero) return;
  w.u8(cm.basis_case);
  w.f32(cm.time_param);
  w.f32(cm.space_param);
  w.u8(uint8_t(cm.coeff_exponent));
  // Exact for quantized coefficients (validate_model checks that they are).
  for (float c : cm.coeffs) w.varint(zigzag_encode(int64_t(std::ldexp(double(c), -cm.coeff_exponent))));
}

std::vector<uint8_t> segment_bytes(const Model& m) {
  ByteWriter w;
  w.u32(uint32_t(m.segments.size()));
  for (const Segment& s : m.segments) {
    w.u32(s.first_frame);
    w.u32(s.last_frame);
    w.u8(uint8_t(s.mode));
    for (const CurveMotion& cm : s.motion) write_motion(w, cm);
  }
  return std::move(w.data());
}


// Bytes of the residual payload's header and chunk index: what RESI holds (the chunks
// follow the sections). The payload is the writer's own, so its index reads.
size_t residual_index_bytes(const Model& m) {
  const std::vector<uint8_t>& p = m.residual.payload;
  ResidualIndex index;
  const bool faces = p.size() > 1 && p[1] != 0;
  return read_residual_index(p.data(), p.size(), m.meta.frame_count, faces, UINT64_MAX, &index, nullptr)
             ? index.index_bytes
             : p.size();
}

std::vector<uint8_t> residual_bytes(const Model& m, size_t index_bytes) {
  ByteWriter w;
  w.f64(m.residual.step);
  for (double o : m.residual.origin) w.f64(o);
  w.bytes(m.residual.payload.data(), index_bytes);
  return std::move(w.data());
}

}  // namespace

size_t motion_record_size(const CurveMotion& m) {
  ByteWriter w;
  write_motion(w, m);
  return w.data().size();
}

namespace {

// The file header: magic, version, flags, section count, where the sections end, its CRC.
ByteWriter file_header(const Model& model, bool render, uint32_t section_count, uint64_t sections_end) {
  ByteWriter out;
  out.bytes(kMagic, 4);
  const bool fast = !model.residual.payload.empty() && model.residual.payload[0] == fast_residual::kPayloadVersion;
  out.u16(fast ? kFastFormatVersionMajor : kFormatVersionMajor);
  const bool scene = render || !model.placement.empty();
  out.u16(fast ? (model.low_rank.components > 0 ? kFastFitBasisFormatVersionMinor
                  : scene                       ? kFastRenderFormatVersionMinor
                                                : kFastFormatVersionMinor)
               : (scene ? kRenderFormatVersionMinor : kFormatVersionMinor));
  out.u32(kFileFlagZeroBlocks | (model.meta.inbetween != Inbetween::Linear ? kFileFlagInbetween : 0));
  out.u32(section_count);
  out.u64(sections_end);
  out.u32(crc32c(out.data().data(), kHeaderBytes - 4));
  return out;
}

// The file in one buffer, reserved once: the header (written last, in front), each section
// (its raw bytes freed once stored), then the chunks. No section is held twice.
std::vector<uint8_t> assemble_container(const Model& model, bool render, size_t index_bytes, const WriteOptions& options,
                                        std::vector<std::pair<uint32_t, std::vector<uint8_t>>>* sections,
                                        std::vector<SectionInfo>* infos) {
  const size_t chunk_bytes = model.residual.step > 0 ? model.residual.payload.size() - index_bytes : 0;
  size_t total = kHeaderBytes + chunk_bytes;
  for (const auto& section : *sections) total += section.second.size() + 32;  // 32: a section header's most
  ByteWriter out;
  out.data().reserve(total);
  out.data().resize(kHeaderBytes);
  if (infos) infos->clear();
  // Positions decode without FACE, REND and PLAC: a reader that skips them is still right.
  for (auto& [tag, raw] : *sections) {
    SectionInfo info = put_section(out, tag, tag != kFaces && tag != kRender && tag != kPlacement && tag != kMaterials,
                                   raw, section_level(tag, raw.size(), options.zstd_level));
    std::vector<uint8_t>().swap(raw);
    if (infos) infos->push_back(std::move(info));
  }
  const ByteWriter header = file_header(model, render, uint32_t(sections->size()), out.size());
  std::copy(header.data().begin(), header.data().end(), out.data().begin());
  // The chunks follow the sections, each checked by its own CRC in the RESI index, so a
  // reader can leave them in the file until a frame needs them.
  if (chunk_bytes > 0) out.bytes(model.residual.payload.data() + index_bytes, chunk_bytes);
  return std::move(out.data());
}

}  // namespace

std::vector<uint8_t> write_container(const Model& model, const WriteOptions& options,
                                     std::vector<SectionInfo>* infos) {
  std::vector<std::pair<uint32_t, std::vector<uint8_t>>> sections;
  sections.emplace_back(kMeta, meta_bytes(model));
  if (options.connectivity && !model.faces.empty()) sections.emplace_back(kFaces, face_bytes(model.faces, options));
  // The common case of neither curves nor segments costs no section at all.
  if (!is_singleton_curves(model.curves, model.meta.vertex_count)) sections.emplace_back(kCurves, curve_bytes(model));
  if (!model.segments.empty()) sections.emplace_back(kSegments, segment_bytes(model));
  if (model.low_rank.components > 0) sections.emplace_back(kLowRank, low_rank_bytes(model));
  size_t index_bytes = 0;
  if (model.residual.step > 0) {
    index_bytes = residual_index_bytes(model);
    sections.emplace_back(kResidual, residual_bytes(model, index_bytes));
  }
  // REND numbers render vertices over the stored faces: without them it has no meaning.
  const bool render = !model.render.empty() && options.connectivity && !model.faces.empty();
  if (render) sections.emplace_back(kRender, render_bytes(model));
  if (!model.placement.empty()) sections.emplace_back(kPlacement, placement_bytes(model));
  if (render && !model.materials.empty()) sections.emplace_back(kMaterials, material_bytes(model));

  return assemble_container(model, render, index_bytes, options, &sections, infos);
}

uint64_t face_payload_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options) {
  return stored_size(face_bytes(faces, options), options.zstd_level);
}

uint64_t face_section_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options) {
  ByteWriter section;
  put_section(section, kFaces, false, face_bytes(faces, options), options.zstd_level);
  return section.data().size();
}

}  // namespace dcurve
