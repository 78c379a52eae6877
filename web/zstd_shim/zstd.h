/* The two zstd functions the decoder calls (codec/decompress/container_reader.cpp), for the
 * WebAssembly build: Emscripten 3.1.6 has no zstd port, so zstd_shim.c forwards to a
 * JavaScript zstd decoder (fzstd) that web/dcurve.js hands to the module. */
#ifndef DCURVE_WEB_ZSTD_SHIM_H
#define DCURVE_WEB_ZSTD_SHIM_H
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Decompresses a whole zstd frame of `size` bytes into dst; returns the decompressed size,
 * or an error code ZSTD_isError recognizes (the data is not zstd, or is larger than
 * `capacity`). */
size_t ZSTD_decompress(void* dst, size_t capacity, const void* src, size_t size);
unsigned ZSTD_isError(size_t code);

#ifdef __cplusplus
}
#endif
#endif
