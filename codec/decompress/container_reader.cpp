#include "codec/decompress/container_reader.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "codec/common/basis.h"
#include "codec/common/bytes.h"
#include "codec/common/crc32.h"
#include "codec/common/fast_residual.h"
#include "codec/common/error.h"
#include "codec/common/render_format.h"
#include "codec/common/residual.h"
#include "codec/common/validate.h"
#include "codec/decompress/faces_decoder.h"
#include "codec/decompress/low_rank_reader.h"
#include "codec/decompress/render_reader.h"
#include "codec/decompress/residual_decoder.h"
#include "codec/decompress/zstd_frame.h"

namespace dcurve {
namespace {

using namespace container_format;  // what both sides of the format share

constexpr uint16_t kSectionKnownFlags = kSectionRequired | kSectionZstd;
// File flags: the low 16 bits name features a reader must understand, the high 16 bits are
// hints a reader may ignore.
constexpr uint32_t kFileRequiredFlagsMask = 0xffffu;
constexpr uint32_t kFileKnownRequiredFlags = kFileFlagZeroBlocks | kFileFlagInbetween;
// Smallest compact section header: tag, flags, a one-byte size, CRC.
constexpr size_t kCompactSectionHeaderMin = 4 + 1 + 1 + 4;
constexpr uint64_t kMaxRawSection = uint64_t(1) << 32;

// has_inbetween: file flag bit 1, META's last field is the in-between rule (format 3.2).
bool parse_meta(ByteReader& r, bool has_inbetween, Model* m) {
  m->meta.vertex_count = r.u32();
  m->meta.frame_count = r.u32();
  m->meta.frame_rate = r.f64();
  m->meta.tolerance = r.f64();
  m->meta.diag = r.f64();
  m->meta.units = r.str(256);
  if (has_inbetween) {
    const uint8_t rule = r.u8();
    if (rule >= kInbetweenCount) return false;
    m->meta.inbetween = Inbetween(rule);
  }
  return r.ok;
}

bool parse_curves(ByteReader& r, Model* m) {
  Curves& c = m->curves;
  uint32_t count = r.u32();
  if (!r.ok || count > r.remaining()) return false;
  c.offsets.assign(1, 0);
  c.closed.clear();
  uint64_t total = 0;
  for (uint32_t i = 0; i < count; ++i) {
    uint64_t z = r.varint();
    total += z >> 1;
    if (!r.ok || total > r.remaining()) return false;
    c.offsets.push_back(uint32_t(total));
    c.closed.push_back(uint8_t(z & 1));
  }
  if (total * 3 > r.remaining()) return false;  // >= 1 byte per id and 2 per u
  c.vertices.resize(size_t(total));
  int64_t prev = 0;
  for (auto& v : c.vertices) {
    if (!add_zigzag_delta(prev, r.varint(), &prev) || prev < 0 || prev > UINT32_MAX) return false;
    v = uint32_t(prev);
  }
  c.u.resize(size_t(total));
  for (auto& u : c.u) u = u_from_fixed(r.u16());
  return r.ok;
}

bool parse_segments(ByteReader& r, Model* m) {
  uint32_t count = r.u32();
  if (!r.ok || uint64_t(count) * 9 > r.remaining()) return false;
  uint64_t motions = uint64_t(m->curves.curve_count()) * 3;
  m->segments.resize(count);
  for (Segment& s : m->segments) {
    s.first_frame = r.u32();
    s.last_frame = r.u32();
    uint8_t mode = r.u8();
    if (mode > uint8_t(FitMode::Displacement)) return false;
    s.mode = FitMode(mode);
    if (!r.ok || motions > r.remaining()) return false;  // >= 1 byte per motion
    s.motion.resize(size_t(motions));
    for (CurveMotion& cm : s.motion) {
      uint8_t b = r.u8();
      if (b > uint8_t(Basis::Pde32)) return false;
      cm.basis = Basis(b);
      if (cm.basis == Basis::Zero) continue;
      cm.basis_case = r.u8();
      cm.time_param = r.f32();
      cm.space_param = r.f32();
      cm.coeff_exponent = int8_t(r.u8());
      if (cm.coeff_exponent < kCoeffExponentMin || cm.coeff_exponent > kCoeffExponentMax) return false;
      cm.coeffs.resize(size_t(basis_term_count(cm.basis)));
      for (float& c : cm.coeffs) {
        const int64_t k = zigzag_decode(r.varint());
        if (k <= -(int64_t(1) << kCoeffIntegerBits) || k >= (int64_t(1) << kCoeffIntegerBits)) return false;
        c = std::ldexp(float(k), cm.coeff_exponent);
      }
      if (!r.ok) return false;
    }
  }
  return r.ok;
}

bool parse_residual(ByteReader& r, Model* m) {
  m->residual.step = r.f64();
  for (double& o : m->residual.origin) o = r.f64();
  const size_t n = r.remaining();
  const uint8_t* p = r.take(n);
  if (!r.ok) return false;
  m->residual.payload.assign(p, p + n);
  return true;
}

// The RESI payload read from a head holds exactly the chunk index, which must describe
// the chunk data_bytes that follow the head.
bool check_chunk_index(Model* m, uint64_t data_bytes, uint16_t major, std::string* error) {
  ResidualIndex index;
  std::string why;
  const std::vector<uint8_t>& p = m->residual.payload;
  if (!read_residual_index(p.data(), p.size(), m->meta.frame_count, !m->faces.empty(), data_bytes, &index, &why))
    return fail(error, "section RESI: " + why);
  if (index.index_bytes != p.size()) return fail(error, "section RESI has bytes after its chunk index");
  if ((index.version == fast_residual::kPayloadVersion) != (major == kFastFormatVersionMajor))
    return fail(error, "section RESI's payload version " + std::to_string(index.version) + " is not that of format " +
                           std::to_string(major));
  if (index.data_bytes != data_bytes)
    return fail(error, "chunk data (" + std::to_string(data_bytes) + " bytes) disagrees with the chunk index (" +
                           std::to_string(index.data_bytes) + " bytes)");
  m->residual.external_bytes = data_bytes;
  m->residual.chunk_frames = index.chunk_frames;
  return true;
}

}  // namespace

uint64_t decoder_value_budget(size_t file_bytes) {
  return std::max(uint64_t(1) << 23, uint64_t(8192) * uint64_t(file_bytes));
}

bool peek_header(const uint8_t* data, size_t size, ContainerHeader* h) {
  ByteReader r(data, size);
  const uint8_t* magic = r.take(4);
  if (!magic || std::memcmp(magic, kMagic, 4) != 0) return false;
  h->version_major = r.u16();
  h->version_minor = r.u16();
  h->flags = r.u32();
  h->section_count = r.u32();
  h->head_bytes = r.u64();
  return r.ok;
}

bool read_container_header(const uint8_t* data, size_t size, uint64_t file_bytes, ContainerHeader* h,
                           std::string* error) {
  ByteReader r(data, size);
  const uint8_t* magic = r.take(4);
  if (!magic || std::memcmp(magic, kMagic, 4) != 0) return fail(error, "not a .dcrv file (bad magic)");
  h->version_major = r.u16();
  h->version_minor = r.u16();  // newer minors only add optional sections and hint flags
  h->flags = r.u32();
  h->section_count = r.u32();
  h->head_bytes = r.u64();
  const uint32_t crc = r.u32();
  if (!r.ok) return fail(error, "truncated header (" + std::to_string(size) + " bytes)");
  if (crc != crc32c(data, kHeaderBytes - 4) && kVerifyChecksums) return fail(error, "header checksum mismatch");
  if (h->version_major != kFormatVersionMajor && h->version_major != kFastFormatVersionMajor)
    return fail(error, "unsupported format version " + std::to_string(h->version_major) + " (this decoder reads " +
                           std::to_string(kFormatVersionMajor) + ".x and " + std::to_string(kFastFormatVersionMajor) +
                           ".x)");
  if (h->flags & kFileRequiredFlagsMask & ~kFileKnownRequiredFlags)
    return fail(error, "file requires features this decoder does not know");
  if (h->head_bytes < kHeaderBytes || h->head_bytes > file_bytes)
    return fail(error, "header's section size points outside the file");
  if (uint64_t(h->section_count) * kCompactSectionHeaderMin > h->head_bytes - kHeaderBytes)
    return fail(error, "section count exceeds file size");
  return true;
}

bool read_container_head(const uint8_t* data, size_t size, uint64_t file_bytes, Model* model, std::string* error,
                         std::vector<SectionInfo>* infos) {
  *model = Model{};
  if (infos) infos->clear();
  ContainerHeader h;
  if (!read_container_header(data, size, file_bytes, &h, error)) return false;
  if (size < h.head_bytes) return fail(error, "file is truncated before its chunk data");
  ByteReader r(data, size_t(h.head_bytes));
  r.take(kHeaderBytes);

  constexpr int kKnown = 9;
  bool seen[kKnown] = {};
  const uint32_t order[kKnown] = {kMeta,     kFaces,  kCurves,    kSegments, kLowRank,
                                  kResidual, kRender, kPlacement, kMaterials};
  std::vector<uint8_t> raw;
  for (uint32_t i = 0; i < h.section_count; ++i) {
    const size_t header_at = r.position();
    const uint32_t tag = r.u32();
    const uint16_t flags = r.u8();
    const uint64_t stored = r.varint();
    const uint64_t raw_size = flags & kSectionZstd ? r.varint() : stored;
    const size_t crc_at = r.position();
    const uint32_t section_crc = r.u32();
    const std::string name = tag_name(tag);
    if (!r.ok) return fail(error, "truncated section header");
    if (stored > r.remaining()) return fail(error, "section " + name + " is truncated");
    const uint8_t* p = r.take(size_t(stored));
    const uint32_t crc_head = crc32c(data + header_at, crc_at - header_at);
    if (crc32c(p, size_t(stored), crc_head) != section_crc && kVerifyChecksums)
      return fail(error, "section " + name + " checksum mismatch");
    if (flags & ~kSectionKnownFlags) return fail(error, "section " + name + " has unknown flags");
    if (infos)
      infos->push_back({name, bool(flags & kSectionRequired), bool(flags & kSectionZstd), header_at,
                        crc_at + 4 - header_at, stored, raw_size, -1});

    int known = -1;
    for (int k = 0; k < kKnown; ++k) if (order[k] == tag) known = k;
    if (known < 0) {
      if (flags & kSectionRequired) return fail(error, "unknown required section " + name);
      continue;  // unknown optional sections are skipped: room to grow
    }
    if (seen[known]) return fail(error, "duplicate section " + name);
    for (int k = known + 1; k < kKnown; ++k)
      if (seen[k]) return fail(error, "section " + name + " out of order");
    seen[known] = true;
    // A file without CURV has one-point curves, which SEGS counts its motions by.
    if (known > 2 && !seen[2] && model->curves.offsets.empty())
      model->curves = singleton_curves(model->meta.vertex_count);

    if (flags & kSectionZstd) {
      const uint64_t budget = decoder_value_budget(size_t(std::min<uint64_t>(file_bytes, SIZE_MAX)));
      if (raw_size > kMaxRawSection || !zstd_size_plausible(raw_size, stored) ||
          (tag == kRender && render_format::kRenderValuesPerByte * raw_size > budget))
        return fail(error, "section " + name + " claims an implausible size");
      if (!decompress_exactly(p, size_t(stored), raw_size, &raw))
        return fail(error, "section " + name + " does not decompress");
    } else {
      raw.assign(p, p + stored);
    }
    ByteReader s(raw.data(), raw.size());
    bool ok = false;
    if (tag == kMeta) {
      ok = parse_meta(s, (h.flags & kFileFlagInbetween) != 0, model);
      // Before anything sized by V or F is built (one-point curves of a file without CURV);
      // F = 0, rejected later, must not let any V through.
      if (ok && uint64_t(model->meta.vertex_count) * std::max(model->meta.frame_count, 1u) >
                    decoder_value_budget(size_t(std::min<uint64_t>(file_bytes, SIZE_MAX))) / 3)
        return fail(error, "vertex and frame counts are implausible for the file size");
    }
    else if (tag == kFaces) {
      if (infos && !raw.empty()) infos->back().face_layout = raw[0];
      std::string why;
      if (!seen[0]) return fail(error, "missing required section META before FACE");  // FACE needs its vertex count
      if (!decode_faces(raw.data(), raw.size(), model->meta.vertex_count, &model->faces, &why))
        return fail(error, "section FACE: " + why);
      s.take(raw.size());
      ok = true;
    }
    else if (tag == kCurves) ok = parse_curves(s, model);
    else if (tag == kSegments) ok = parse_segments(s, model);
    else if (tag == kLowRank) ok = seen[0] && parse_low_rank(s, model, h.version_major == kFastFormatVersionMajor);
    else if (tag == kResidual) ok = parse_residual(s, model);
    else if (tag == kRender) ok = seen[0] && parse_render(s, model);
    else if (tag == kPlacement) ok = parse_placement(s, model);
    else if (tag == kMaterials) ok = parse_materials(s, model);
    if (!ok || s.remaining() != 0) return fail(error, "section " + name + " is malformed");
  }
  if (r.remaining() != 0) return fail(error, "the sections end before the header's chunk data offset");
  if (!seen[0]) return fail(error, "missing required section " + tag_name(order[0]));
  if (!seen[2] && model->curves.offsets.empty())
    model->curves = singleton_curves(model->meta.vertex_count);
  if (!seen[3]) model->segments.clear();
  const std::vector<uint8_t>& basis = model->low_rank.basis_payload;
  if (!basis.empty() && basis[0] == fast_residual::kPayloadVersion && h.version_major != kFastFormatVersionMajor)
    return fail(error, "section LRNK's basis is a format 4 payload in a file of format " +
                           std::to_string(h.version_major));
  if (seen[5]) {
    if (!check_chunk_index(model, file_bytes - h.head_bytes, h.version_major, error)) return false;
  } else if (file_bytes != h.head_bytes) {
    return fail(error, "trailing bytes after the last section");
  }
  return validate_model(*model, error);
}

bool read_container(const uint8_t* data, size_t size, Model* model, std::string* error,
                    std::vector<SectionInfo>* infos) {
  if (!read_container_head(data, size, size, model, error, infos)) return false;
  // The chunks follow the head: the payload holds them after its index, as the writer's.
  // With the whole file at hand every chunk's checksum is verified now.
  ResidualLayer& res = model->residual;
  if (res.external_bytes > 0) {
    const uint8_t* chunks = data + (size - res.external_bytes);
    ResidualIndex index;
    read_residual_index(res.payload.data(), res.payload.size(), model->meta.frame_count, !model->faces.empty(),
                        res.external_bytes, &index, nullptr);
    for (size_t c = 0; c < index.chunks.size(); ++c)
      if (kVerifyChecksums && crc32c(chunks + index.chunks[c].offset, size_t(index.chunks[c].size)) != index.chunks[c].crc)
        return fail(error, "chunk " + std::to_string(c) + " is corrupted (checksum mismatch)");
    res.payload.insert(res.payload.end(), chunks, chunks + res.external_bytes);
    res.external_bytes = 0;
  }
  return true;
}

}  // namespace dcurve
