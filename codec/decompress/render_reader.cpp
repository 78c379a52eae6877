#include "codec/decompress/render_reader.h"

#include <cmath>
#include <cstdint>
#include <vector>

#include "codec/common/render_format.h"
#include "codec/common/render_mesh.h"

namespace dcurve {
namespace {

// Varints of at least one byte each: the count is checked against the bytes left first.
bool read_varints(ByteReader& r, size_t count, std::vector<uint32_t>* out) {
  if (count > r.remaining()) return false;
  out->resize(count);
  for (uint32_t& j : *out) {
    const uint64_t v = r.varint();
    if (v > UINT32_MAX) return false;
    j = uint32_t(v);
  }
  return r.ok;
}

// "New vertex" (0) or a distance d back from the next new one.
bool read_source(ByteReader& r, size_t render_count, uint32_t vertex_count, std::vector<uint32_t>* source) {
  if (!read_varints(r, render_count, source)) return false;
  uint32_t next = 0;
  for (uint32_t& v : *source) {
    if (v == 0) {
      if (next == vertex_count) return false;
      v = next++;
    } else {
      if (v > next) return false;
      v = next - v;
    }
  }
  return next == vertex_count;
}

bool read_range(ByteReader& r, RenderAttribute* a) {
  for (uint32_t c = 0; c < a->components; ++c) {
    a->lo[c] = r.f32();
    a->hi[c] = r.f32();
    if (!std::isfinite(a->lo[c]) || !std::isfinite(a->hi[c]) || a->lo[c] > a->hi[c]) return false;
  }
  return r.ok;
}

bool read_attribute(ByteReader& r, size_t render_count, int previous_semantic, RenderAttribute* a) {
  const uint8_t semantic = r.u8();
  a->components = r.u8();
  a->bits = r.u8();
  if (!r.ok || semantic >= kAttributeSemanticCount || int(semantic) <= previous_semantic) return false;
  a->semantic = AttributeSemantic(semantic);
  if (!attribute_components_allowed(a->semantic, a->components) || a->bits < 1 || a->bits > kMaxAttributeBits ||
      !read_range(r, a))
    return false;
  const size_t values = render_count * a->components;
  if (values > r.remaining()) return false;
  a->q.resize(values);
  const int64_t top = (int64_t(1) << a->bits) - 1;
  for (uint32_t c = 0; c < a->components; ++c) {
    int64_t q = 0;
    for (size_t v = 0; v < render_count; ++v) {
      if (!add_zigzag_delta(q, r.varint(), &q) || q < 0 || q > top) return false;
      a->q[v * a->components + c] = uint16_t(q);
    }
  }
  return r.ok;
}

// Groups and, with any, the group of each triangle.
bool read_groups(ByteReader& r, size_t triangles, RenderMesh* render) {
  const uint64_t count = r.varint();
  if (!r.ok || count > r.remaining() / 2) return false;  // a material varint and a name length each
  render->groups.resize(size_t(count));
  for (FaceGroup& g : render->groups) {
    const uint64_t material = r.varint();
    if (material > uint64_t(INT32_MAX)) return false;
    g.material = int32_t(material) - 1;
    g.name = r.str(render_format::kMaxNameBytes);
  }
  if (!r.ok || count == 0) return r.ok;
  if (!read_varints(r, triangles, &render->face_group)) return false;
  for (uint32_t g : render->face_group)
    if (g >= count) return false;
  return true;
}

}  // namespace

bool parse_render(ByteReader& r, Model* model) {
  if (r.u8() != render_format::kVersion || model->faces.empty()) return false;
  const uint64_t render_count = r.varint();
  if (!r.ok || render_count < model->meta.vertex_count || render_count > r.remaining()) return false;
  std::vector<uint32_t> ordinals;
  RenderMesh& render = model->render;
  if (!read_source(r, size_t(render_count), model->meta.vertex_count, &render.source) ||
      !read_varints(r, model->faces.size(), &ordinals) ||
      !render_corners_from_ordinals(model->faces, render.source, model->meta.vertex_count, ordinals, &render.corners))
    return false;
  const uint8_t count = r.u8();
  if (!r.ok || count > kAttributeSemanticCount) return false;
  render.attributes.resize(count);
  int previous = -1;
  for (RenderAttribute& a : render.attributes) {
    if (!read_attribute(r, size_t(render_count), previous, &a)) return false;
    previous = int(a.semantic);
  }
  return read_groups(r, model->faces.size() / 3, &render);
}

bool parse_materials(ByteReader& r, Model* model) {
  MaterialSet& m = model->materials;
  if (r.u8() != render_format::kVersion) return false;
  m.json = r.str(r.remaining());
  const uint64_t count = r.varint();
  if (!r.ok || count > r.remaining() / 2) return false;  // a media type length and a size each
  m.images.resize(size_t(count));
  for (MaterialImage& image : m.images) {
    image.mime_type = r.str(render_format::kMaxMimeBytes);
    const uint64_t size = r.varint();
    if (!r.ok || size > r.remaining()) return false;
    const uint8_t* p = r.take(size_t(size));
    image.bytes.assign(p, p + size);
  }
  return r.ok;
}

bool parse_placement(ByteReader& r, Model* model) {
  Placement& p = model->placement;
  if (r.u8() != render_format::kVersion) return false;
  p.start_time = r.f64();
  const uint8_t has_matrix = r.u8();
  if (!r.ok || !std::isfinite(p.start_time) || has_matrix > 1) return false;
  p.has_matrix = has_matrix == 1;
  if (p.has_matrix)
    for (double& x : p.matrix)
      if (x = r.f64(); !std::isfinite(x)) return false;
  p.mesh_name = r.str(render_format::kMaxNameBytes);
  p.node_name = r.str(render_format::kMaxNameBytes);
  return r.ok;
}

}  // namespace dcurve
