#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <vector>

#include "codec/container.h"
#include "codec/residual.h"
#include "dcurve.hpp"
#include "frame_evaluator.h"
#include "model_prediction.h"

namespace dcurve {

struct Decoder::Impl {
  Model model;
  FrameEvaluator evaluator;  // points into `model`: both live and die together
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
  std::vector<int32_t> q;
  const Model& m = impl->model;
  // read_container checked V * F * 3 against the same budget (zstd can expand a section
  // 4096-fold, so the residual's own bound alone would not do).
  const uint64_t budget = decoder_value_budget(size);
  if (m.residual.step > 0) {
    // Files with a motion model may predict frames from it: its grid values come first.
    std::vector<int32_t> prediction;
    ResidualOptions options;
    if (has_model_prediction(m)) {
      if (!model_grid_prediction(m, budget, &prediction, error)) return nullptr;
      options.model_prediction = &prediction;
    }
    if (!decode_residuals(m, &q, error, options)) return nullptr;
  }
  if (!impl->evaluator.build(m, q, budget, error)) return nullptr;
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
  impl_->evaluator.evaluate(double(std::min(f, frame_count() - 1)), xyz);
}

void Decoder::evaluate(double t, float* xyz) const {
  // Clamping happens in frame coordinates; NaN maps to frame 0.
  impl_->evaluator.evaluate(t * double(frame_count() - 1), xyz);
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
