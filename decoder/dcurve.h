/* dcurve runtime decoder, C ABI. Thin wrapper over dcurve.hpp for engines and other languages.
 * Every function that can fail returns 0 on success and a non-zero code otherwise; the
 * message is copied into `error` (always NUL-terminated when error_size > 0). A NULL decoder
 * is accepted everywhere: counts read 0, evaluation writes nothing. */
#ifndef DCURVE_H
#define DCURVE_H
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dcurve_decoder dcurve_decoder;

/* Opens a .dcrv held in memory; the caller may free `data` afterwards. Returns 1 with a
 * message on malformed input (*out = NULL), 2 when `out` is NULL. */
int dcurve_open_memory(const void* data, size_t size, dcurve_decoder** out, char* error, size_t error_size);
/* Opens a .dcrv file by path. */
int dcurve_open_file(const char* path, dcurve_decoder** out, char* error, size_t error_size);
void dcurve_close(dcurve_decoder* decoder);

uint32_t dcurve_vertex_count(const dcurve_decoder* decoder);
uint32_t dcurve_frame_count(const dcurve_decoder* decoder);
uint32_t dcurve_face_count(const dcurve_decoder* decoder);
/* 3 * face_count vertex ids, or NULL when the file omits connectivity. Owned by the decoder. */
const uint32_t* dcurve_faces(const dcurve_decoder* decoder);

/* Writes vertex_count * 3 floats for t in [0, 1] (clamped). No allocation; thread-safe. */
void dcurve_evaluate(const dcurve_decoder* decoder, double t, float* xyz_out);
/* Exact reconstruction of input frame f (clamped to [0, frame_count)). */
void dcurve_evaluate_frame(const dcurve_decoder* decoder, uint32_t frame, float* xyz_out);
/* Unit vertex normals of `xyz`; returns non-zero when the file has no connectivity. */
int dcurve_compute_normals(const dcurve_decoder* decoder, const float* xyz, float* normals_out);

#ifdef __cplusplus
}
#endif
#endif
