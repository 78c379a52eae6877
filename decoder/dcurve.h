/* dcurve runtime decoder, C ABI. Thin wrapper over dcurve.hpp for engines and other languages.
 *
 * Every function that can fail returns DCURVE_OK (0) on success and one of the
 * DCURVE_ERROR_* codes otherwise; the message is copied into `error` (always
 * NUL-terminated when error_size > 0; `error` may be NULL). No C++ exception crosses this
 * interface. A NULL decoder or cursor is accepted everywhere: counts read 0, evaluation
 * writes nothing and returns DCURVE_ERROR_INVALID_ARGUMENT.
 *
 * Threads: a decoder is immutable once opened and may be shared by threads; a cursor
 * belongs to one thread at a time. dcurve_evaluate* on the decoder itself lock an internal
 * cursor (safe from any thread, one call at a time); give each playing thread a cursor.
 * Memory: the decoder keeps the compressed chunks (open_memory) or reads them from the
 * file on demand (open_file); each cursor holds one decoded chunk and the frame before it,
 * and under a cubic in-between rule copies of up to six frames. */
#ifndef DCURVE_H
#define DCURVE_H
#include <stddef.h>
#include <stdint.h>

#define DCURVE_VERSION_MAJOR 0
#define DCURVE_VERSION_MINOR 4
#define DCURVE_VERSION_PATCH 0
#define DCURVE_VERSION ((DCURVE_VERSION_MAJOR << 16) | (DCURVE_VERSION_MINOR << 8) | DCURVE_VERSION_PATCH)
/* The newest .dcrv format major version this library reads (it reads 3 and 4). */
#define DCURVE_FORMAT_VERSION_MAJOR 4

#define DCURVE_OK 0
#define DCURVE_ERROR_MALFORMED 1        /* not a valid .dcrv, or a format version not read here */
#define DCURVE_ERROR_INVALID_ARGUMENT 2 /* NULL output pointer, NULL decoder or cursor */
#define DCURVE_ERROR_IO 3               /* the file cannot be opened or read */
#define DCURVE_ERROR_CORRUPT_CHUNK 4    /* a chunk fails its checksum or does not decode */
#define DCURVE_ERROR_OUT_OF_MEMORY 5
#define DCURVE_ERROR_INTERNAL 6

/* In-between rules (format 3.2): how evaluation fills the time between stored frames. */
#define DCURVE_INTERPOLATION_LINEAR 0
#define DCURVE_INTERPOLATION_CATMULL_ROM 1
#define DCURVE_INTERPOLATION_HERMITE4 2

/* Static attributes of render vertices (format 3.3 / 4.1), the glTF attribute names. */
#define DCURVE_ATTRIBUTE_TEXCOORD_0 0
#define DCURVE_ATTRIBUTE_TEXCOORD_1 1
#define DCURVE_ATTRIBUTE_COLOR_0 2
#define DCURVE_ATTRIBUTE_NORMAL 3

#ifdef __cplusplus
extern "C" {
#endif

typedef struct dcurve_decoder dcurve_decoder;
typedef struct dcurve_cursor dcurve_cursor;

/* DCURVE_VERSION of the linked library (compare with the header's macro). */
uint32_t dcurve_version(void);
/* A static name for a status code ("ok", "malformed", ...); "unknown" for others. */
const char* dcurve_status_name(int status);

/* Opens a .dcrv held in memory; the caller may free `data` afterwards. */
int dcurve_open_memory(const void* data, size_t size, dcurve_decoder** out, char* error, size_t error_size);
/* Opens a .dcrv file by path; chunks are read from the file when needed. */
int dcurve_open_file(const char* path, dcurve_decoder** out, char* error, size_t error_size);
void dcurve_close(dcurve_decoder* decoder);

uint32_t dcurve_vertex_count(const dcurve_decoder* decoder);
uint32_t dcurve_frame_count(const dcurve_decoder* decoder);
uint32_t dcurve_face_count(const dcurve_decoder* decoder);
/* 3 * face_count vertex ids, or NULL when the file omits connectivity. Owned by the decoder. */
const uint32_t* dcurve_faces(const dcurve_decoder* decoder);
double dcurve_frame_rate(const dcurve_decoder* decoder);    /* frames per second; 0 unknown */
double dcurve_tolerance(const dcurve_decoder* decoder);     /* max error, fraction of L */
double dcurve_rest_diagonal(const dcurve_decoder* decoder); /* L, model units */
uint32_t dcurve_chunk_frames(const dcurve_decoder* decoder);
/* The in-between rule the file records (DCURVE_INTERPOLATION_*; files before 3.2: linear). */
int dcurve_interpolation(const dcurve_decoder* decoder);
/* Overrides the rule for the decoder's own evaluate calls; DCURVE_ERROR_INVALID_ARGUMENT for
 * an unknown rule. */
int dcurve_set_interpolation(dcurve_decoder* decoder, int rule);
/* Bytes the decoder holds now (shared tables, kept chunks, its internal cursor). */
size_t dcurve_memory_bytes(const dcurve_decoder* decoder);

/* Writes vertex_count * 3 floats for t in [0, 1] (clamped; NaN reads as 0). */
int dcurve_evaluate(const dcurve_decoder* decoder, double t, float* xyz_out);
/* Exact reconstruction of input frame f (clamped to [0, frame_count)). */
int dcurve_evaluate_frame(const dcurve_decoder* decoder, uint32_t frame, float* xyz_out);
/* The same with the failure's message (a chunk that fails its checksum, a file truncated
 * after opening). */
int dcurve_evaluate_ex(const dcurve_decoder* decoder, double t, float* xyz_out, char* error, size_t error_size);
/* Unit vertex normals of `xyz`; returns non-zero when the file has no connectivity. */
int dcurve_compute_normals(const dcurve_decoder* decoder, const float* xyz, float* normals_out);

/* Render vertices: what a game draws. A file made from a mesh with UV or normal seams splits a
 * vertex into copies at the same position; positions are coded once per vertex, so copies
 * never drift apart. Without such data (files before 3.3) render vertices are the vertices. */
uint32_t dcurve_render_vertex_count(const dcurve_decoder* decoder);
/* render_vertex_count ids: the vertex whose position each render vertex shows; NULL when
 * render vertices are the vertices. Owned by the decoder. */
const uint32_t* dcurve_render_source(const dcurve_decoder* decoder);
/* 3 * face_count render vertex ids, the triangles of dcurve_faces in the same order; NULL
 * when render vertices are the vertices (use dcurve_faces). */
const uint32_t* dcurve_render_faces(const dcurve_decoder* decoder);
/* Components of a DCURVE_ATTRIBUTE_* (2 for texture coordinates, 3 for normals, 3 or 4 for
 * colours), 0 when the file has none; the values: render_vertex_count * components floats
 * owned by the decoder, or NULL. */
uint32_t dcurve_attribute_components(const dcurve_decoder* decoder, int attribute);
const float* dcurve_attribute(const dcurve_decoder* decoder, int attribute);
/* Positions of render vertices (render_vertex_count * 3 floats) from vertex positions. */
int dcurve_render_positions(const dcurve_decoder* decoder, const float* xyz, float* render_xyz_out);
/* Unit normals of render vertices from vertex positions: copies of a vertex share one normal,
 * smooth across UV seams, unless the input's own normals differ there (a hard edge). */
int dcurve_compute_render_normals(const dcurve_decoder* decoder, const float* xyz, float* normals_out);
/* Face groups (one per material of the input; 0 for a file without them). Group i covers
 * triangles [first_face, first_face + face_count) of dcurve_group_faces; material indexes the
 * "materials" of dcurve_materials_json (-1: none); name is owned by the decoder. */
uint32_t dcurve_group_count(const dcurve_decoder* decoder);
int dcurve_group(const dcurve_decoder* decoder, uint32_t i, uint32_t* first_face, uint32_t* face_count, int* material,
                 const char** name);
/* 3 * face_count render ids ordered by group, or NULL without groups. */
const uint32_t* dcurve_group_faces(const dcurve_decoder* decoder);
/* The groups' materials as a glTF JSON object ("materials", "textures", "samplers", "images";
 * "" without them) and the images' bytes (image i of "images"), owned by the decoder. */
const char* dcurve_materials_json(const dcurve_decoder* decoder);
uint32_t dcurve_image_count(const dcurve_decoder* decoder);
const uint8_t* dcurve_image(const dcurve_decoder* decoder, uint32_t i, size_t* size, const char** mime_type);
/* Placement (PLAC): seconds of frame 0 in the input's timeline (0 when unknown); the world
 * transform of the input's node, column-major, written to matrix_out (identity and return 0
 * when the file has none, 1 when it has one); the input's mesh and node names ("" if none). */
double dcurve_start_time(const dcurve_decoder* decoder);
int dcurve_world_matrix(const dcurve_decoder* decoder, double matrix_out[16]);
const char* dcurve_mesh_name(const dcurve_decoder* decoder);
const char* dcurve_node_name(const dcurve_decoder* decoder);

/* A playback cursor for one thread; must be destroyed before its decoder is closed. */
int dcurve_cursor_create(const dcurve_decoder* decoder, dcurve_cursor** out);
void dcurve_cursor_destroy(dcurve_cursor* cursor);
int dcurve_cursor_evaluate(dcurve_cursor* cursor, double t, float* xyz_out, char* error, size_t error_size);
int dcurve_cursor_evaluate_frame(dcurve_cursor* cursor, uint32_t frame, float* xyz_out, char* error,
                                 size_t error_size);
size_t dcurve_cursor_memory_bytes(const dcurve_cursor* cursor);
/* Overrides the in-between rule of this cursor (it starts with the file's). */
int dcurve_cursor_set_interpolation(dcurve_cursor* cursor, int rule);

#ifdef __cplusplus
}
#endif
#endif
