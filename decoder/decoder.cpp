#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

#include "codec/container.h"
#include "codec/residual.h"
#include "dcurve.hpp"

namespace dcurve {

struct Decoder::Impl {
  Model model;
  // Reconstructed input frames, frame-major, xyz per vertex: the exact grid positions.
  std::vector<float> frames;
};

Decoder::Decoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Decoder::~Decoder() = default;

std::unique_ptr<Decoder> Decoder::open_memory(const void* data, size_t size, std::string* error) {
  auto impl = std::make_unique<Impl>();
  if (!data && size) {
    if (error) *error = "null data";
    return nullptr;
  }
  if (!read_container(static_cast<const uint8_t*>(data), size, &impl->model, error)) return nullptr;
  for (const Segment& s : impl->model.segments)
    for (const CurveMotion& m : s.motion)
      if (m.basis != Basis::Zero) {
        if (error) *error = "file uses a PDE motion model, which this decoder build does not evaluate yet";
        return nullptr;
      }
  std::vector<int32_t> q;
  if (!decode_residuals(impl->model, &q, error)) return nullptr;
  const ResidualLayer& r = impl->model.residual;
  impl->frames.resize(q.size());
  for (size_t i = 0; i < q.size(); ++i) impl->frames[i] = float(r.origin[i % 3] + r.step * double(q[i]));
  return std::unique_ptr<Decoder>(new Decoder(std::move(impl)));
}

std::unique_ptr<Decoder> Decoder::open_file(const std::string& path, std::string* error) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (error) *error = path + ": cannot open file";
    return nullptr;
  }
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string err;
  auto d = open_memory(bytes.data(), bytes.size(), &err);
  if (!d && error) *error = path + ": " + err;
  return d;
}

uint32_t Decoder::vertex_count() const { return impl_->model.meta.vertex_count; }
uint32_t Decoder::frame_count() const { return impl_->model.meta.frame_count; }
uint32_t Decoder::face_count() const { return uint32_t(impl_->model.faces.size() / 3); }
const uint32_t* Decoder::faces() const { return impl_->model.faces.empty() ? nullptr : impl_->model.faces.data(); }
double Decoder::frame_rate() const { return impl_->model.meta.frame_rate; }
double Decoder::tolerance() const { return impl_->model.meta.tolerance; }
double Decoder::rest_diagonal() const { return impl_->model.meta.diag; }

void Decoder::evaluate_frame(uint32_t f, float* xyz) const {
  const size_t n = size_t(vertex_count()) * 3;
  f = std::min(f, frame_count() - 1);
  std::copy_n(impl_->frames.data() + f * n, n, xyz);
}

void Decoder::evaluate(double t, float* xyz) const {
  const uint32_t F = frame_count();
  const size_t n = size_t(vertex_count()) * 3;
  if (!(t > 0.0) || F == 1) return evaluate_frame(0, xyz);  // also catches NaN
  if (t >= 1.0) return evaluate_frame(F - 1, xyz);
  double x = t * double(F - 1);
  uint32_t i = std::min(uint32_t(x), F - 2);
  float w = float(x - double(i));
  const float* a = impl_->frames.data() + i * n;
  const float* b = a + n;
  for (size_t k = 0; k < n; ++k) xyz[k] = a[k] + w * (b[k] - a[k]);
}

bool Decoder::compute_normals(const float* xyz, float* normals) const {
  const auto& faces = impl_->model.faces;
  if (faces.empty()) return false;
  const size_t V = vertex_count();
  std::fill_n(normals, V * 3, 0.f);
  for (size_t t = 0; t + 2 < faces.size(); t += 3) {
    const float* p0 = xyz + 3 * faces[t];
    const float* p1 = xyz + 3 * faces[t + 1];
    const float* p2 = xyz + 3 * faces[t + 2];
    float e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
    float e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
    // The unnormalized cross product weights each face by its area.
    float c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) normals[3 * faces[t + k] + a] += c[a];
  }
  for (size_t v = 0; v < V; ++v) {
    float* nv = normals + 3 * v;
    float len = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
    if (len > 0.f) for (int a = 0; a < 3; ++a) nv[a] /= len;
  }
  return true;
}

}  // namespace dcurve
