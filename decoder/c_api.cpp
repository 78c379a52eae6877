// The C ABI over dcurve.hpp. Every entry point catches everything: no C++ exception
// crosses into a C caller.
#include <cstring>
#include <new>
#include <string>

#include "dcurve.h"
#include "dcurve.hpp"

struct dcurve_decoder {
  std::unique_ptr<dcurve::Decoder> d;
};
struct dcurve_cursor {
  std::unique_ptr<dcurve::Cursor> c;
};

namespace {
void copy_message(const std::string& message, char* error, size_t error_size) {
  if (!error || error_size == 0) return;
  const size_t n = std::min(message.size(), error_size - 1);
  std::memcpy(error, message.data(), n);
  error[n] = '\0';
}

int report(const dcurve::Error& e, char* error, size_t error_size) {
  copy_message(e.message, error, error_size);
  return int(e.status);
}

int finish(std::unique_ptr<dcurve::Decoder> d, const std::string& err, dcurve::Status status, dcurve_decoder** out,
           char* error, size_t error_size) {
  if (!d) {
    copy_message(err, error, error_size);
    *out = nullptr;
    return status == dcurve::Status::Ok ? DCURVE_ERROR_INTERNAL : int(status);
  }
  *out = new dcurve_decoder{std::move(d)};
  return DCURVE_OK;
}

// Runs an entry point's body, turning any escaping exception into a status.
template <class Body>
int guarded(char* error, size_t error_size, Body body) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    copy_message("out of memory", error, error_size);
    return DCURVE_ERROR_OUT_OF_MEMORY;
  } catch (...) {
    copy_message("internal error", error, error_size);
    return DCURVE_ERROR_INTERNAL;
  }
}

template <class Target>
int evaluate_with(Target* target, double t, bool frame, float* xyz, char* error, size_t error_size) {
  if (!target || !xyz) {
    copy_message("null decoder, cursor or output", error, error_size);
    return DCURVE_ERROR_INVALID_ARGUMENT;
  }
  return guarded(error, error_size, [&] {
    dcurve::Error e;
    const bool ok = frame ? target->evaluate_frame(uint32_t(t), xyz, &e) : target->evaluate(t, xyz, &e);
    return ok ? DCURVE_OK : report(e, error, error_size);
  });
}
}  // namespace

extern "C" {
uint32_t dcurve_version(void) { return DCURVE_VERSION; }

const char* dcurve_status_name(int status) {
  switch (status) {
    case DCURVE_OK: return "ok";
    case DCURVE_ERROR_MALFORMED: return "malformed";
    case DCURVE_ERROR_INVALID_ARGUMENT: return "invalid argument";
    case DCURVE_ERROR_IO: return "i/o error";
    case DCURVE_ERROR_CORRUPT_CHUNK: return "corrupt chunk";
    case DCURVE_ERROR_OUT_OF_MEMORY: return "out of memory";
    case DCURVE_ERROR_INTERNAL: return "internal error";
  }
  return "unknown";
}

int dcurve_open_memory(const void* data, size_t size, dcurve_decoder** out, char* error, size_t error_size) {
  if (!out) return DCURVE_ERROR_INVALID_ARGUMENT;
  *out = nullptr;
  return guarded(error, error_size, [&] {
    std::string err;
    dcurve::Status status = dcurve::Status::Ok;
    auto d = dcurve::Decoder::open_memory(data, size, &err, &status);
    return finish(std::move(d), err, status, out, error, error_size);
  });
}

int dcurve_open_file(const char* path, dcurve_decoder** out, char* error, size_t error_size) {
  if (!out) return DCURVE_ERROR_INVALID_ARGUMENT;
  *out = nullptr;
  return guarded(error, error_size, [&] {
    std::string err;
    dcurve::Status status = dcurve::Status::Ok;
    auto d = dcurve::Decoder::open_file(path ? path : "", &err, &status);
    return finish(std::move(d), err, status, out, error, error_size);
  });
}

void dcurve_close(dcurve_decoder* decoder) { delete decoder; }

// A NULL decoder (a failed open the caller did not check) reads as an empty mesh.
uint32_t dcurve_vertex_count(const dcurve_decoder* d) { return d ? d->d->vertex_count() : 0; }
uint32_t dcurve_frame_count(const dcurve_decoder* d) { return d ? d->d->frame_count() : 0; }
uint32_t dcurve_face_count(const dcurve_decoder* d) { return d ? d->d->face_count() : 0; }
const uint32_t* dcurve_faces(const dcurve_decoder* d) { return d ? d->d->faces() : nullptr; }
double dcurve_frame_rate(const dcurve_decoder* d) { return d ? d->d->frame_rate() : 0.0; }
double dcurve_tolerance(const dcurve_decoder* d) { return d ? d->d->tolerance() : 0.0; }
double dcurve_rest_diagonal(const dcurve_decoder* d) { return d ? d->d->rest_diagonal() : 0.0; }
uint32_t dcurve_chunk_frames(const dcurve_decoder* d) { return d ? d->d->chunk_frames() : 0; }
size_t dcurve_memory_bytes(const dcurve_decoder* d) { return d ? d->d->memory_bytes() : 0; }
int dcurve_interpolation(const dcurve_decoder* d) { return d ? int(d->d->interpolation()) : DCURVE_INTERPOLATION_LINEAR; }

static bool known_interpolation(int rule) {
  return rule >= DCURVE_INTERPOLATION_LINEAR && rule <= DCURVE_INTERPOLATION_HERMITE4;
}
int dcurve_set_interpolation(dcurve_decoder* d, int rule) {
  if (!d || !known_interpolation(rule)) return DCURVE_ERROR_INVALID_ARGUMENT;
  d->d->set_interpolation(dcurve::Interpolation(rule));
  return DCURVE_OK;
}

int dcurve_evaluate(const dcurve_decoder* d, double t, float* xyz) {
  return evaluate_with(d ? d->d.get() : nullptr, t, false, xyz, nullptr, 0);
}
int dcurve_evaluate_frame(const dcurve_decoder* d, uint32_t f, float* xyz) {
  return evaluate_with(d ? d->d.get() : nullptr, double(f), true, xyz, nullptr, 0);
}
int dcurve_evaluate_ex(const dcurve_decoder* d, double t, float* xyz, char* error, size_t error_size) {
  return evaluate_with(d ? d->d.get() : nullptr, t, false, xyz, error, error_size);
}
int dcurve_compute_normals(const dcurve_decoder* d, const float* xyz, float* n) {
  return d && xyz && n && d->d->compute_normals(xyz, n) ? DCURVE_OK : DCURVE_ERROR_INVALID_ARGUMENT;
}

uint32_t dcurve_render_vertex_count(const dcurve_decoder* d) { return d ? d->d->render_vertex_count() : 0; }
const uint32_t* dcurve_render_source(const dcurve_decoder* d) { return d ? d->d->render_source() : nullptr; }
const uint32_t* dcurve_render_faces(const dcurve_decoder* d) { return d ? d->d->render_faces() : nullptr; }

static bool known_attribute(int a) { return a >= DCURVE_ATTRIBUTE_TEXCOORD_0 && a <= DCURVE_ATTRIBUTE_NORMAL; }
uint32_t dcurve_attribute_components(const dcurve_decoder* d, int a) {
  return d && known_attribute(a) ? d->d->attribute_components(dcurve::Attribute(a)) : 0;
}
const float* dcurve_attribute(const dcurve_decoder* d, int a) {
  return d && known_attribute(a) ? d->d->attribute(dcurve::Attribute(a)) : nullptr;
}
int dcurve_render_positions(const dcurve_decoder* d, const float* xyz, float* out) {
  if (!d || !xyz || !out) return DCURVE_ERROR_INVALID_ARGUMENT;
  d->d->render_positions(xyz, out);
  return DCURVE_OK;
}
int dcurve_compute_render_normals(const dcurve_decoder* d, const float* xyz, float* n) {
  if (!d || !xyz || !n) return DCURVE_ERROR_INVALID_ARGUMENT;
  return guarded(nullptr, 0, [&] { return d->d->compute_render_normals(xyz, n) ? DCURVE_OK : DCURVE_ERROR_INVALID_ARGUMENT; });
}
uint32_t dcurve_group_count(const dcurve_decoder* d) { return d ? d->d->group_count() : 0; }
int dcurve_group(const dcurve_decoder* d, uint32_t i, uint32_t* first, uint32_t* count, int* material, const char** name) {
  if (!d || i >= d->d->group_count()) return DCURVE_ERROR_INVALID_ARGUMENT;
  const dcurve::Group g = d->d->group(i);
  if (first) *first = g.first_face;
  if (count) *count = g.face_count;
  if (material) *material = g.material;
  // The decoder's own copy: stable while it is open.
  if (name) *name = d->d->group_name(i).c_str();
  return DCURVE_OK;
}
const uint32_t* dcurve_group_faces(const dcurve_decoder* d) { return d ? d->d->group_faces() : nullptr; }
const char* dcurve_materials_json(const dcurve_decoder* d) { return d ? d->d->materials_json().c_str() : ""; }
uint32_t dcurve_image_count(const dcurve_decoder* d) { return d ? d->d->image_count() : 0; }
const uint8_t* dcurve_image(const dcurve_decoder* d, uint32_t i, size_t* size, const char** mime_type) {
  if (size) *size = 0;
  if (mime_type) *mime_type = "";
  if (!d || i >= d->d->image_count()) return nullptr;
  if (mime_type) *mime_type = d->d->image_mime_type(i).c_str();
  return d->d->image(i, size);
}
double dcurve_start_time(const dcurve_decoder* d) { return d ? d->d->start_time() : 0.0; }
int dcurve_world_matrix(const dcurve_decoder* d, double matrix[16]) {
  static const double identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  if (!matrix) return 0;
  if (!d) {
    std::memcpy(matrix, identity, sizeof identity);
    return 0;
  }
  return d->d->world_matrix(matrix) ? 1 : 0;
}
const char* dcurve_mesh_name(const dcurve_decoder* d) { return d ? d->d->mesh_name().c_str() : ""; }
const char* dcurve_node_name(const dcurve_decoder* d) { return d ? d->d->node_name().c_str() : ""; }

int dcurve_cursor_create(const dcurve_decoder* d, dcurve_cursor** out) {
  if (!out) return DCURVE_ERROR_INVALID_ARGUMENT;
  *out = nullptr;
  if (!d) return DCURVE_ERROR_INVALID_ARGUMENT;
  return guarded(nullptr, 0, [&] {
    *out = new dcurve_cursor{d->d->make_cursor()};
    return DCURVE_OK;
  });
}
void dcurve_cursor_destroy(dcurve_cursor* cursor) { delete cursor; }
int dcurve_cursor_evaluate(dcurve_cursor* c, double t, float* xyz, char* error, size_t error_size) {
  return evaluate_with(c ? c->c.get() : nullptr, t, false, xyz, error, error_size);
}
int dcurve_cursor_evaluate_frame(dcurve_cursor* c, uint32_t f, float* xyz, char* error, size_t error_size) {
  return evaluate_with(c ? c->c.get() : nullptr, double(f), true, xyz, error, error_size);
}
size_t dcurve_cursor_memory_bytes(const dcurve_cursor* c) { return c ? c->c->memory_bytes() : 0; }
int dcurve_cursor_set_interpolation(dcurve_cursor* c, int rule) {
  if (!c || !known_interpolation(rule)) return DCURVE_ERROR_INVALID_ARGUMENT;
  c->c->set_interpolation(dcurve::Interpolation(rule));
  return DCURVE_OK;
}
}
