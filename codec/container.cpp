#include "codec/container.h"

#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "codec/basis.h"
#include "codec/bytes.h"
#include "codec/crc32.h"
#include "codec/error.h"
#include "codec/faces.h"
#include "codec/low_rank.h"
#include "codec/residual.h"
#include "codec/validate.h"

namespace dcurve {
namespace {

constexpr char kMagic[4] = {'D', 'C', 'R', 'V'};
constexpr size_t kHeaderBytes = kContainerHeaderBytes;
constexpr uint16_t kSectionRequired = 1;
constexpr uint16_t kSectionZstd = 2;
constexpr uint16_t kSectionKnownFlags = kSectionRequired | kSectionZstd;
// File flags: the low 16 bits name features a reader must understand (none in 3.0), the
// high 16 bits are hints a reader may ignore.
constexpr uint32_t kFileRequiredFlagsMask = 0xffffu;
constexpr uint32_t kFileKnownRequiredFlags = 0;
// Smallest compact section header: tag, flags, a one-byte size, CRC.
constexpr size_t kCompactSectionHeaderMin = 4 + 1 + 1 + 4;
// A decompressed section may be at most this many times its stored size (plus a floor):
// the bound that keeps a hostile file from asking for unbounded memory.
constexpr uint64_t kMaxExpansion = 4096;
constexpr uint64_t kExpansionFloor = 1u << 20;
constexpr uint64_t kMaxRawSection = uint64_t(1) << 32;

uint32_t fourcc(const char* s) {
  return uint32_t(uint8_t(s[0])) | uint32_t(uint8_t(s[1])) << 8 | uint32_t(uint8_t(s[2])) << 16 |
         uint32_t(uint8_t(s[3])) << 24;
}
std::string tag_name(uint32_t t) {
  std::string s(4, '?');
  for (int i = 0; i < 4; ++i) {
    char c = char((t >> (8 * i)) & 0xff);
    s[i] = (c >= 32 && c < 127) ? c : '?';
  }
  return s;
}

const uint32_t kMeta = fourcc("META");
const uint32_t kFaces = fourcc("FACE");
const uint32_t kCurves = fourcc("CURV");
const uint32_t kSegments = fourcc("SEGS");
const uint32_t kLowRank = fourcc("LRNK");
const uint32_t kResidual = fourcc("RESI");

// The bytes a section stores: zstd when that is smaller, else the raw bytes.
std::vector<uint8_t> stored_form(const std::vector<uint8_t>& raw, int level, bool* compressed) {
  std::vector<uint8_t> stored(ZSTD_compressBound(raw.size()));
  size_t n = ZSTD_compress(stored.data(), stored.size(), raw.data(), raw.size(), level);
  *compressed = !ZSTD_isError(n) && n < raw.size();
  if (*compressed) stored.resize(n); else stored = raw;
  return stored;
}

std::vector<uint8_t> face_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options) {
  using Layout = WriteOptions::FaceLayout;
  std::vector<uint8_t> best = encode_faces(faces, FaceOrder::Exact);
  if (options.face_layout == Layout::Exact) return best;
  bool unused;
  auto stored_size = [&](const std::vector<uint8_t>& raw) { return stored_form(raw, options.zstd_level, &unused).size(); };
  auto consider = [&](std::vector<uint8_t> raw, Layout layout) {
    if (options.face_layout == layout || (options.face_layout == Layout::Smallest && stored_size(raw) < stored_size(best)))
      best = std::move(raw);
  };
  // Compact reproduces any list exactly (encode_faces falls back to Exact beyond its bound).
  consider(encode_faces(faces, FaceOrder::Compact), Layout::Compact);
  // Traversal may reorder triangles, and other parts of the file (the residual coder's
  // neighbours) were built on model.faces: a candidate only when it gives them back as is.
  std::vector<uint8_t> traversal = encode_faces(faces, FaceOrder::Traversal);
  std::vector<uint32_t> back;
  if (decode_faces(traversal.data(), traversal.size(), &back, nullptr) && back == faces)
    consider(std::move(traversal), Layout::Traversal);
  return best;
}

// A section header: tag, u8 flags, varint stored
// size, varint raw size only when compressed, CRC.
void put_section(ByteWriter& out, uint32_t tag, bool required, const std::vector<uint8_t>& raw,
                 int level) {
  bool compressed = false;
  std::vector<uint8_t> stored = stored_form(raw, level, &compressed);
  const size_t header_at = out.size();
  out.u32(tag);
  out.u8(uint8_t((required ? kSectionRequired : 0) | (compressed ? kSectionZstd : 0)));
  out.varint(stored.size());
  if (compressed) out.varint(raw.size());
  // The checksum covers the section header too: a flipped tag or flag must not turn a
  // section into an unknown optional one that a reader would silently skip.
  uint32_t crc = crc32c(out.data().data() + header_at, out.size() - header_at);
  out.u32(crc32c(stored.data(), stored.size(), crc));
  out.bytes(stored.data(), stored.size());
}

std::vector<uint8_t> meta_bytes(const Model& m) {
  ByteWriter w;
  w.u32(m.meta.vertex_count);
  w.u32(m.meta.frame_count);
  w.f64(m.meta.frame_rate);
  w.f64(m.meta.tolerance);
  w.f64(m.meta.diag);
  w.str(m.meta.units);
  return std::move(w.data());
}

uint16_t u_to_fixed(float u) { return uint16_t(std::lround(std::clamp(u, 0.f, 1.f) * 65535.f)); }
float u_from_fixed(uint16_t q) { return float(q) / 65535.f; }

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

bool parse_meta(ByteReader& r, Model* m) {
  m->meta.vertex_count = r.u32();
  m->meta.frame_count = r.u32();
  m->meta.frame_rate = r.f64();
  m->meta.tolerance = r.f64();
  m->meta.diag = r.f64();
  m->meta.units = r.str(256);
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
bool check_chunk_index(Model* m, uint64_t data_bytes, std::string* error) {
  ResidualIndex index;
  std::string why;
  const std::vector<uint8_t>& p = m->residual.payload;
  if (!read_residual_index(p.data(), p.size(), m->meta.frame_count, !m->faces.empty(), data_bytes, &index, &why))
    return fail(error, "section RESI: " + why);
  if (index.index_bytes != p.size()) return fail(error, "section RESI has bytes after its chunk index");
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

Curves singleton_curves(uint32_t V) {
  Curves c;
  c.vertices.resize(V);
  c.offsets.resize(size_t(V) + 1);
  c.closed.assign(V, 0);
  c.u.assign(V, 0.f);
  for (uint32_t v = 0; v < V; ++v) c.vertices[v] = c.offsets[v] = v;
  c.offsets[V] = V;
  return c;
}

bool is_singleton_curves(const Curves& c, uint32_t V) {
  if (c.curve_count() != V || c.vertices.size() != V || c.u.size() != V || c.closed.size() != V) return false;
  for (uint32_t v = 0; v < V; ++v)
    if (c.vertices[v] != v || c.offsets[v] != v || c.closed[v] != 0 || c.u[v] != 0.f) return false;
  return c.offsets[V] == V;
}

size_t motion_record_size(const CurveMotion& m) {
  ByteWriter w;
  write_motion(w, m);
  return w.data().size();
}

std::vector<uint8_t> write_container(const Model& model, const WriteOptions& options) {
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

  ByteWriter body;
  for (const auto& [tag, raw] : sections) put_section(body, tag, tag != kFaces, raw, options.zstd_level);
  ByteWriter out;
  out.bytes(kMagic, 4);
  out.u16(kFormatVersionMajor);
  out.u16(kFormatVersionMinor);
  out.u32(0);
  out.u32(uint32_t(sections.size()));
  out.u64(kHeaderBytes + body.size());
  out.u32(crc32c(out.data().data(), kHeaderBytes - 4));
  out.bytes(body.data().data(), body.size());
  // The chunks follow the sections, each checked by its own CRC in the RESI index, so a
  // reader can leave them in the file until a frame needs them.
  if (model.residual.step > 0)
    out.bytes(model.residual.payload.data() + index_bytes, model.residual.payload.size() - index_bytes);
  return std::move(out.data());
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

float quantize_curve_u(float u) { return u_from_fixed(u_to_fixed(u)); }

int quantize_coefficients(CurveMotion* m, int exponent) {
  double largest = 0;
  for (float c : m->coeffs) largest = std::max(largest, std::fabs(double(c)));
  // |k| = |c| / 2^e rounds to at most 2^24 - 1 when 2^e >= |c| / (2^24 - 1).
  if (largest > 0 && std::isfinite(largest))
    exponent = std::max(exponent, int(std::ceil(std::log2(largest / double((1 << kCoeffIntegerBits) - 1)))));
  exponent = std::min(std::max(exponent, kCoeffExponentMin), kCoeffExponentMax);
  m->coeff_exponent = int8_t(exponent);
  for (float& c : m->coeffs)
    c = std::ldexp(float(std::round(std::ldexp(double(c), -exponent))), exponent);
  return exponent;
}

uint64_t face_payload_bytes(const std::vector<uint32_t>& faces, const WriteOptions& options) {
  bool unused;
  return stored_form(face_bytes(faces, options), options.zstd_level, &unused).size();
}

uint64_t connectivity_bytes(const std::vector<SectionInfo>& sections) {
  uint64_t bytes = 0;
  for (const SectionInfo& s : sections)
    if (s.tag == "FACE") bytes += s.stored_bytes + s.header_bytes;
  return bytes;
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
  if (h->version_major != kFormatVersionMajor)
    return fail(error, "unsupported format version " + std::to_string(h->version_major) + " (this decoder reads " +
                           std::to_string(kFormatVersionMajor) + ".x)");
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

  constexpr int kKnown = 6;
  bool seen[kKnown] = {false, false, false, false, false, false};
  const uint32_t order[kKnown] = {kMeta, kFaces, kCurves, kSegments, kLowRank, kResidual};
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
      if (raw_size > kMaxRawSection || raw_size > std::max(kExpansionFloor, stored * kMaxExpansion))
        return fail(error, "section " + name + " claims an implausible size");
      raw.resize(size_t(raw_size));
      size_t n = ZSTD_decompress(raw.data(), raw.size(), p, size_t(stored));
      if (ZSTD_isError(n) || n != raw_size) return fail(error, "section " + name + " does not decompress");
    } else {
      raw.assign(p, p + stored);
    }
    ByteReader s(raw.data(), raw.size());
    bool ok = false;
    if (tag == kMeta) {
      ok = parse_meta(s, model);
      // Before anything sized by V or F is built (one-point curves of a file without CURV);
      // F = 0, rejected later, must not let any V through.
      if (ok && uint64_t(model->meta.vertex_count) * std::max(model->meta.frame_count, 1u) >
                    decoder_value_budget(size_t(std::min<uint64_t>(file_bytes, SIZE_MAX))) / 3)
        return fail(error, "vertex and frame counts are implausible for the file size");
    }
    else if (tag == kFaces) {
      if (infos && !raw.empty()) infos->back().face_layout = raw[0];
      std::string why;
      if (!decode_faces(raw.data(), raw.size(), &model->faces, &why)) return fail(error, "section FACE: " + why);
      s.take(raw.size());
      ok = true;
    }
    else if (tag == kCurves) ok = parse_curves(s, model);
    else if (tag == kSegments) ok = parse_segments(s, model);
    else if (tag == kLowRank) ok = seen[0] && parse_low_rank(s, model);
    else if (tag == kResidual) ok = parse_residual(s, model);
    if (!ok || s.remaining() != 0) return fail(error, "section " + name + " is malformed");
  }
  if (r.remaining() != 0) return fail(error, "the sections end before the header's chunk data offset");
  if (!seen[0]) return fail(error, "missing required section " + tag_name(order[0]));
  if (!seen[2] && model->curves.offsets.empty())
    model->curves = singleton_curves(model->meta.vertex_count);
  if (!seen[3]) model->segments.clear();
  if (seen[5]) {
    if (!check_chunk_index(model, file_bytes - h.head_bytes, error)) return false;
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
