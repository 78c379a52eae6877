#include <cstring>
#include <string>

#include "dcurve.h"
#include "dcurve.hpp"

struct dcurve_decoder {
  std::unique_ptr<dcurve::Decoder> d;
};

namespace {
int finish(std::unique_ptr<dcurve::Decoder> d, const std::string& err, dcurve_decoder** out, char* error,
           size_t error_size) {
  if (!out) return 2;
  if (!d) {
    if (error && error_size > 0) {
      size_t n = std::min(err.size(), error_size - 1);
      std::memcpy(error, err.data(), n);
      error[n] = '\0';
    }
    *out = nullptr;
    return 1;
  }
  *out = new dcurve_decoder{std::move(d)};
  return 0;
}
}  // namespace

extern "C" {
int dcurve_open_memory(const void* data, size_t size, dcurve_decoder** out, char* error, size_t error_size) {
  std::string err;
  auto d = dcurve::Decoder::open_memory(data, size, &err);
  return finish(std::move(d), err, out, error, error_size);
}
int dcurve_open_file(const char* path, dcurve_decoder** out, char* error, size_t error_size) {
  std::string err;
  auto d = dcurve::Decoder::open_file(path ? path : "", &err);
  return finish(std::move(d), err, out, error, error_size);
}
void dcurve_close(dcurve_decoder* decoder) { delete decoder; }
// A NULL decoder (a failed open the caller did not check) reads as an empty mesh.
uint32_t dcurve_vertex_count(const dcurve_decoder* d) { return d ? d->d->vertex_count() : 0; }
uint32_t dcurve_frame_count(const dcurve_decoder* d) { return d ? d->d->frame_count() : 0; }
uint32_t dcurve_face_count(const dcurve_decoder* d) { return d ? d->d->face_count() : 0; }
const uint32_t* dcurve_faces(const dcurve_decoder* d) { return d ? d->d->faces() : nullptr; }
void dcurve_evaluate(const dcurve_decoder* d, double t, float* xyz) {
  if (d && xyz) d->d->evaluate(t, xyz);
}
void dcurve_evaluate_frame(const dcurve_decoder* d, uint32_t f, float* xyz) {
  if (d && xyz) d->d->evaluate_frame(f, xyz);
}
int dcurve_compute_normals(const dcurve_decoder* d, const float* xyz, float* n) {
  return d && xyz && n && d->d->compute_normals(xyz, n) ? 0 : 1;
}
}
