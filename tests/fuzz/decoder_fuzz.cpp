// libFuzzer entry: any bytes -> Decoder::open_memory, and when a file opens, evaluate it at
// frames and between them (through the decoder and through a cursor playing the first
// frames in order, then in-betweens under a cubic rule), with normals, then read what REND,
// PLAC and MATL hold through the render, attribute, group and material calls. A crash,
// sanitizer report, leak, failure without a message, an id out of range or an attribute value
// that is not finite is a finding.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dcurve.hpp"

namespace {

void check(bool ok) {
  if (!ok) __builtin_trap();
}

// Render vertices show vertices, render triangles use render vertices, attributes are finite.
void read_render(const dcurve::Decoder& dec, const std::vector<float>& xyz) {
  const uint32_t R = dec.render_vertex_count(), V = dec.vertex_count();
  if (const uint32_t* source = dec.render_source())
    for (uint32_t r = 0; r < R; ++r) check(source[r] < V);
  if (const uint32_t* faces = dec.render_faces())
    for (size_t k = 0; k < 3 * size_t(dec.face_count()); ++k) check(faces[k] < R);
  for (auto a : {dcurve::Attribute::TexCoord0, dcurve::Attribute::TexCoord1, dcurve::Attribute::Color0,
                 dcurve::Attribute::Normal}) {
    const float* values = dec.attribute(a);
    const size_t n = size_t(dec.attribute_components(a)) * R;
    check((values != nullptr) == (n > 0));
    for (size_t i = 0; i < n; ++i) check(std::isfinite(values[i]));
  }
  std::vector<float> render_xyz(3 * size_t(R)), normals(render_xyz.size());
  dec.render_positions(xyz.data(), render_xyz.data());
  dec.compute_render_normals(xyz.data(), normals.data());
}

// Groups cover the render triangles in order; materials and images as stored.
void read_groups_and_materials(const dcurve::Decoder& dec) {
  uint64_t faces = 0;
  for (uint32_t g = 0; g < dec.group_count(); ++g) {
    const dcurve::Group group = dec.group(g);
    check(group.first_face == faces && group.name == dec.group_name(g) && group.material >= -1);
    faces += group.face_count;
  }
  check(dec.group_count() == 0 || (faces == dec.face_count() && dec.group_faces() != nullptr));
  for (uint32_t i = 0; i < dec.image_count(); ++i) {
    size_t size = 0;
    const uint8_t* bytes = dec.image(i, &size);
    check(size == 0 || bytes != nullptr);
    check(dec.image_mime_type(i).size() <= 64);
  }
  double matrix[16];
  if (dec.world_matrix(matrix))
    for (double x : matrix) check(std::isfinite(x));
  check(std::isfinite(dec.start_time()) && dec.mesh_name().size() <= 1024 && dec.node_name().size() <= 1024);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string error;
  auto dec = dcurve::Decoder::open_memory(data, size, &error);
  if (!dec) {
    if (error.empty()) __builtin_trap();  // every rejection must say why
    return 0;
  }
  std::vector<float> xyz(size_t(dec->vertex_count()) * 3), normals(xyz.size());
  dcurve::Error e;
  for (double t : {0.0, 0.37, 0.5, 1.0, -3.0, 7.0})
    if (!dec->evaluate(t, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  dec->evaluate_frame(dec->frame_count() - 1, xyz.data());
  auto cursor = dec->make_cursor();
  for (uint32_t f = 0; f < std::min<uint32_t>(dec->frame_count(), 40); ++f)
    if (!cursor->evaluate_frame(f, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  // A cubic in-between rule reaches up to six frames in up to four chunks.
  cursor->set_interpolation(dcurve::Interpolation::Hermite4);
  for (double t : {0.37, 0.05, 0.93})
    if (!cursor->evaluate(t, xyz.data(), &e) && e.message.empty()) __builtin_trap();
  dec->compute_normals(xyz.data(), normals.data());
  read_render(*dec, xyz);
  read_groups_and_materials(*dec);
  return 0;
}
