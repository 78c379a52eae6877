#include "codec/compress/render_writer.h"

#include <cstdint>
#include <vector>

#include "codec/common/bytes.h"
#include "codec/common/render_format.h"
#include "codec/common/render_mesh.h"

namespace dcurve {
namespace {

// Each component as the zigzagged difference from the previous render vertex's: neighbours
// in first-use order are neighbours on the surface, so the differences are small.
void write_attribute(ByteWriter& w, const RenderAttribute& a, size_t render_count) {
  w.u8(uint8_t(a.semantic));
  w.u8(a.components);
  w.u8(a.bits);
  for (uint32_t c = 0; c < a.components; ++c) {
    w.f32(a.lo[c]);
    w.f32(a.hi[c]);
  }
  for (uint32_t c = 0; c < a.components; ++c) {
    int64_t previous = 0;
    for (size_t r = 0; r < render_count; ++r) {
      const int64_t q = a.q[r * a.components + c];
      w.varint(zigzag_encode(q - previous));
      previous = q;
    }
  }
}

}  // namespace

std::vector<uint8_t> render_bytes(const Model& model) {
  const RenderMesh& render = model.render;
  std::vector<uint32_t> ordinals;
  render_corner_ordinals(model.faces, render, model.meta.vertex_count, &ordinals);  // checked by validate_model
  ByteWriter w;
  w.u8(render_format::kVersion);
  w.varint(render.source.size());
  // Each render vertex shows the next new vertex (0) or one `d` back from it (d >= 1).
  uint32_t next = 0;
  for (uint32_t v : render.source) {
    w.varint(v == next ? 0 : next - v);
    if (v == next) ++next;
  }
  for (uint32_t j : ordinals) w.varint(j);
  w.u8(uint8_t(render.attributes.size()));
  for (const RenderAttribute& a : render.attributes) write_attribute(w, a, render.source.size());
  w.varint(render.groups.size());
  for (const FaceGroup& g : render.groups) {
    w.varint(uint64_t(int64_t(g.material) + 1));
    w.str(g.name);
  }
  if (!render.groups.empty())
    for (uint32_t g : render.face_group) w.varint(g);
  return std::move(w.data());
}

std::vector<uint8_t> material_bytes(const Model& model) {
  const MaterialSet& m = model.materials;
  ByteWriter w;
  w.u8(render_format::kVersion);
  w.str(m.json);
  w.varint(m.images.size());
  for (const MaterialImage& image : m.images) {
    w.str(image.mime_type);
    w.varint(image.bytes.size());
    w.bytes(image.bytes.data(), image.bytes.size());
  }
  return std::move(w.data());
}

std::vector<uint8_t> placement_bytes(const Model& model) {
  const Placement& p = model.placement;
  ByteWriter w;
  w.u8(render_format::kVersion);
  w.f64(p.start_time);
  w.u8(p.has_matrix ? 1 : 0);
  if (p.has_matrix)
    for (double x : p.matrix) w.f64(x);
  w.str(p.mesh_name);
  w.str(p.node_name);
  return std::move(w.data());
}

}  // namespace dcurve
