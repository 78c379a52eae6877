#!/usr/bin/env bash
# Builds the decoder (codec/common, codec/decompress, decoder/: no encoder code) to
# WebAssembly: web/build/dcurve_wasm.mjs (an ES module factory) and dcurve_wasm.wasm.
# Needs Emscripten (Debian's `emscripten`); without it, prints a message and exits 0
# unless DCURVE_WEB_REQUIRED=1. Usage: web/build.sh [JOBS=2]
set -euo pipefail
web=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$web")
out=$web/build
jobs=${1:-2}

if ! command -v emcc >/dev/null; then
  echo "web/build.sh: emcc not found (apt-get install emscripten); the WebAssembly decoder is not built" >&2
  [ "${DCURVE_WEB_REQUIRED:-0}" = 1 ] && exit 1
  exit 0
fi

# -Os: size first, the hot loops are integer arithmetic that -Os keeps fast. No exception
# catching (Emscripten's default): the C API reports every error by status and message, and
# only out-of-memory would throw, which aborts the module (web/dcurve.js reports it).
cflags=(-Os -DNDEBUG -I"$root" -I"$root/decoder" -I"$web/zstd_shim")
sources=("$root"/codec/common/*.cpp "$root"/codec/decompress/*.cpp "$root"/decoder/*.cpp "$web"/zstd_shim/zstd_shim.c)

# Emscripten's JS optimizer needs Debian's node-acorn, in /usr/share/nodejs, which a node not
# from Debian (e.g. NodeSource's) does not search.
[ -d /usr/share/nodejs ] && export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}

mkdir -p "$out/obj"
compile_one() {  # source -> obj/<dir>_<name>.o, rebuilt when the source is newer
  local src=$1 obj
  obj=$out/obj/$(basename "$(dirname "$src")")_$(basename "$src").o
  [ "$obj" -nt "$src" ] && return 0
  case $src in
    *.c) emcc "${cflags[@]}" -c "$src" -o "$obj" ;;
    *) em++ -std=c++17 "${cflags[@]}" -c "$src" -o "$obj" ;;
  esac
}
export -f compile_one
export out
export cflags_str="${cflags[*]}"
# Headers change rarely; a header edit needs `rm -r web/build` (the script is a build step of
# the tests, not an incremental build system).
printf '%s\n' "${sources[@]}" | xargs -P "$jobs" -I{} bash -c 'cflags=($cflags_str); compile_one "$1"' _ {}

exported=_malloc,_free,_dcurve_open_memory,_dcurve_close,_dcurve_vertex_count,_dcurve_frame_count,\
_dcurve_face_count,_dcurve_faces,_dcurve_frame_rate,_dcurve_tolerance,_dcurve_rest_diagonal,\
_dcurve_chunk_frames,_dcurve_memory_bytes,_dcurve_compute_normals,_dcurve_cursor_create,\
_dcurve_cursor_destroy,_dcurve_cursor_evaluate,_dcurve_cursor_evaluate_frame,_dcurve_cursor_memory_bytes
em++ -Os "$out"/obj/*.o -o "$out/dcurve_wasm.mjs" \
  -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=createDcurveModule -sENVIRONMENT=web \
  -sFILESYSTEM=0 -sALLOW_MEMORY_GROWTH=1 -sEXPORTED_FUNCTIONS="$exported" \
  -sEXPORTED_RUNTIME_METHODS=HEAPU8,HEAPF32,HEAPU32 --no-entry
echo "web/build.sh: built $out/dcurve_wasm.mjs and dcurve_wasm.wasm"
