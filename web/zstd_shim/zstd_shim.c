/* ZSTD_decompress through the module's `zstdDecompress` (fzstd's decompress, given by
 * web/dcurve.js): only the few small shared sections of a .dcrv are zstd-compressed, so a
 * JavaScript decoder costs little time and keeps zstd's sources out of the wasm. */
#include <emscripten.h>

#include "zstd.h"

/* Error codes as zstd spells them: the top of the size_t range. */
#define SHIM_ERROR ((size_t)-1)
#define SHIM_MAX_ERROR_CODE 120

/* Returns the decompressed size, or -1 when the frame does not decode or does not fit. */
EM_JS(int, dcurve_js_zstd_decompress, (void* dst, int capacity, const void* src, int size), {
  try {
    const out = Module["zstdDecompress"](HEAPU8.subarray(src, src + size));
    if (out.length > capacity) return -1;
    HEAPU8.set(out, dst);
    return out.length;
  } catch (e) {
    return -1;
  }
});

size_t ZSTD_decompress(void* dst, size_t capacity, const void* src, size_t size) {
  if (capacity > 0x7fffffff || size > 0x7fffffff) return SHIM_ERROR;
  const int n = dcurve_js_zstd_decompress(dst, (int)capacity, src, (int)size);
  return n < 0 ? SHIM_ERROR : (size_t)n;
}

unsigned ZSTD_isError(size_t code) { return code > (size_t)-SHIM_MAX_ERROR_CODE; }
