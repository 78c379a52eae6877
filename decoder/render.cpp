// Render vertices, their attributes and the placement (REND, PLAC) as the Decoder gives them.
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "codec/common/model.h"
#include "codec/common/render_mesh.h"
#include "decoder_state.h"
#include "dcurve.hpp"
#include "normals.h"

namespace dcurve {
namespace {

// Copies of a vertex share a normal unless the file's NORMAL attribute tells them apart.
void build_normal_groups(const RenderMesh& render, RenderState* state) {
  const size_t R = render.source.size();
  const RenderAttribute* normal = nullptr;
  for (const RenderAttribute& a : render.attributes)
    if (a.semantic == AttributeSemantic::Normal) normal = &a;
  auto key = [&](uint32_t r, uint32_t c) { return normal ? normal->q[size_t(r) * 3 + c] : 0u; };
  auto less = [&](uint32_t a, uint32_t b) {
    if (render.source[a] != render.source[b]) return render.source[a] < render.source[b];
    for (uint32_t c = 0; c < 3; ++c)
      if (key(a, c) != key(b, c)) return key(a, c) < key(b, c);
    return false;
  };
  std::vector<uint32_t> order(R);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), less);
  state->normal_group.assign(R, 0);
  uint32_t group = 0;
  for (size_t i = 0; i < R; ++i) {
    if (i > 0 && less(order[i - 1], order[i])) ++group;
    state->normal_group[order[i]] = group;
  }
  state->normal_groups = R ? group + 1 : 0;
  state->corner_group.resize(render.corners.size());
  for (size_t k = 0; k < render.corners.size(); ++k) state->corner_group[k] = state->normal_group[render.corners[k]];
}

// Render triangles in group order (stable: each group's keep the faces' order).
void build_groups(const RenderMesh& render, RenderState* state) {
  if (render.groups.empty()) return;
  const size_t G = render.groups.size(), T = render.face_group.size();
  state->group_first.assign(G + 1, 0);
  for (uint32_t g : render.face_group) ++state->group_first[g + 1];
  for (size_t g = 0; g < G; ++g) state->group_first[g + 1] += state->group_first[g];
  std::vector<uint32_t> next(state->group_first.begin(), state->group_first.end() - 1);
  state->group_faces.resize(3 * T);
  for (size_t t = 0; t < T; ++t)
    std::copy_n(render.corners.data() + 3 * t, 3, state->group_faces.data() + 3 * size_t(next[render.face_group[t]]++));
}

}  // namespace

void build_render_state(Model* model, RenderState* state) {
  *state = RenderState{};
  RenderMesh& render = model->render;
  if (render.empty()) return;
  for (const RenderAttribute& a : render.attributes) {
    const size_t s = size_t(a.semantic);
    state->components[s] = a.components;
    state->attributes[s].resize(render.source.size() * a.components);
    for (size_t r = 0; r < render.source.size(); ++r)
      for (uint32_t c = 0; c < a.components; ++c) state->attributes[s][r * a.components + c] = a.value(r, c);
  }
  build_normal_groups(render, state);
  build_groups(render, state);
  for (RenderAttribute& a : render.attributes) std::vector<uint16_t>().swap(a.q);
}

size_t RenderState::memory_bytes() const {
  size_t bytes = (normal_group.capacity() + corner_group.capacity() + group_faces.capacity() + group_first.capacity()) * 4;
  for (const std::vector<float>& a : attributes) bytes += a.capacity() * 4;
  return bytes;
}

uint32_t Decoder::render_vertex_count() const {
  const RenderMesh& r = impl_->shared.model.render;
  return r.empty() ? vertex_count() : uint32_t(r.source.size());
}

const uint32_t* Decoder::render_source() const {
  const RenderMesh& r = impl_->shared.model.render;
  return r.empty() ? nullptr : r.source.data();
}

const uint32_t* Decoder::render_faces() const {
  const RenderMesh& r = impl_->shared.model.render;
  return r.empty() ? nullptr : r.corners.data();
}

uint32_t Decoder::attribute_components(Attribute a) const {
  const size_t s = size_t(a);
  return s < kAttributeSemanticCount ? impl_->shared.render.components[s] : 0;
}

const float* Decoder::attribute(Attribute a) const {
  const size_t s = size_t(a);
  if (s >= kAttributeSemanticCount || impl_->shared.render.attributes[s].empty()) return nullptr;
  return impl_->shared.render.attributes[s].data();
}

void Decoder::render_positions(const float* xyz, float* out) const {
  const RenderMesh& r = impl_->shared.model.render;
  if (r.empty()) {
    std::copy_n(xyz, size_t(vertex_count()) * 3, out);
    return;
  }
  for (size_t i = 0; i < r.source.size(); ++i) std::copy_n(xyz + 3 * size_t(r.source[i]), 3, out + 3 * i);
}

bool Decoder::compute_render_normals(const float* xyz, float* normals) const {
  const Model& m = impl_->shared.model;
  if (m.render.empty()) return compute_normals(xyz, normals);
  const RenderState& state = impl_->shared.render;
  std::vector<float> group_normals(size_t(state.normal_groups) * 3);
  area_normals(xyz, m.faces.data(), m.faces.size(), state.corner_group.data(), state.normal_groups,
               group_normals.data());
  for (size_t i = 0; i < m.render.source.size(); ++i)
    std::copy_n(group_normals.data() + 3 * size_t(state.normal_group[i]), 3, normals + 3 * i);
  return true;
}

uint32_t Decoder::group_count() const { return uint32_t(impl_->shared.model.render.groups.size()); }

Group Decoder::group(uint32_t i) const {
  const RenderMesh& r = impl_->shared.model.render;
  if (i >= r.groups.size()) return Group{};
  const std::vector<uint32_t>& first = impl_->shared.render.group_first;
  return Group{first[i], first[i + 1] - first[i], r.groups[i].material, r.groups[i].name};
}

const std::string& Decoder::group_name(uint32_t i) const {
  static const std::string none;
  const RenderMesh& r = impl_->shared.model.render;
  return i < r.groups.size() ? r.groups[i].name : none;
}

const uint32_t* Decoder::group_faces() const {
  const std::vector<uint32_t>& f = impl_->shared.render.group_faces;
  return f.empty() ? nullptr : f.data();
}

const std::string& Decoder::materials_json() const { return impl_->shared.model.materials.json; }
uint32_t Decoder::image_count() const { return uint32_t(impl_->shared.model.materials.images.size()); }

const uint8_t* Decoder::image(uint32_t i, size_t* size) const {
  const auto& images = impl_->shared.model.materials.images;
  if (size) *size = i < images.size() ? images[i].bytes.size() : 0;
  return i < images.size() ? images[i].bytes.data() : nullptr;
}

const std::string& Decoder::image_mime_type(uint32_t i) const {
  static const std::string none;
  const auto& images = impl_->shared.model.materials.images;
  return i < images.size() ? images[i].mime_type : none;
}

double Decoder::start_time() const { return impl_->shared.model.placement.start_time; }

bool Decoder::world_matrix(double out[16]) const {
  const Placement& p = impl_->shared.model.placement;
  std::copy_n(p.matrix, 16, out);
  return p.has_matrix;
}

const std::string& Decoder::mesh_name() const { return impl_->shared.model.placement.mesh_name; }
const std::string& Decoder::node_name() const { return impl_->shared.model.placement.node_name; }

}  // namespace dcurve
