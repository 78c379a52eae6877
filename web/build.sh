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

# -O2 for the sources (per-frame decode is clearly faster than with -Os in web/bench.mjs, for
# a few KB more gzip'ed wasm) with WebAssembly SIMD (-msimd128: the low-rank sums' 16-bit
# multiply-adds; every current browser runs it: Chrome 91, Firefox 89, Safari 16.4 on), -Os
# for the link (wasm-opt, the glue's minification). No exception
# catching (Emscripten's default): the C API reports every error by status and message, and
# only out-of-memory would throw, which aborts the module (web/dcurve.js reports it).
cflags=(-O2 -msimd128 -DNDEBUG -I"$root" -I"$root/decoder" -I"$web/zstd_shim")

# Emscripten's JS optimizer needs Debian's node-acorn, in /usr/share/nodejs, which a node not
# from Debian (e.g. NodeSource's) does not search.
[ -d /usr/share/nodejs ] && export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}

# Unity batches of 8 sources per folder, as the native build's (CMAKE_UNITY_BUILD, which the
# sources are written for), compiled $jobs at a time: a clean build in about half the CPU time
# of one compile per file. Always rebuilt: this is a step of the tests, not a build system.
rm -rf "$out/obj"
mkdir -p "$out/obj"
units=()
for dir in codec/common codec/decompress decoder; do
  files=("$root/$dir"/*.cpp)
  for ((i = 0; i < ${#files[@]}; i += 8)); do
    unit=$out/obj/${dir//\//_}_$((i / 8)).cpp
    printf '#include "%s"\n' "${files[@]:i:8}" >"$unit"
    units+=("$unit")
  done
done
for unit in "${units[@]}" "$web/zstd_shim/zstd_shim.c"; do
  [ "$(jobs -rp | wc -l)" -ge "$jobs" ] && wait -n
  case $unit in
    *.c) emcc "${cflags[@]}" -c "$unit" -o "$out/obj/zstd_shim.o" & ;;
    *) em++ -std=c++17 "${cflags[@]}" -c "$unit" -o "$unit.o" & ;;
  esac
done
for pid in $(jobs -p); do wait "$pid"; done  # fails the script if any compile failed

exported=_malloc,_free,_dcurve_open_memory,_dcurve_close,_dcurve_vertex_count,_dcurve_frame_count,\
_dcurve_face_count,_dcurve_faces,_dcurve_frame_rate,_dcurve_tolerance,_dcurve_rest_diagonal,\
_dcurve_chunk_frames,_dcurve_memory_bytes,_dcurve_compute_normals,_dcurve_cursor_create,\
_dcurve_cursor_destroy,_dcurve_cursor_evaluate,_dcurve_cursor_evaluate_frame,_dcurve_cursor_memory_bytes,\
_dcurve_status_name,_dcurve_render_vertex_count,_dcurve_render_source,_dcurve_render_faces,\
_dcurve_attribute_components,_dcurve_attribute,_dcurve_render_positions,_dcurve_compute_render_normals,\
_dcurve_group_count,_dcurve_group,_dcurve_group_faces,_dcurve_materials_json,_dcurve_image_count,_dcurve_image,\
_dcurve_start_time,_dcurve_world_matrix,_dcurve_mesh_name,_dcurve_node_name
em++ -Os "$out"/obj/*.o -o "$out/dcurve_wasm.mjs" \
  -sMODULARIZE=1 -sEXPORT_ES6=1 -sEXPORT_NAME=createDcurveModule -sENVIRONMENT=web \
  -sFILESYSTEM=0 -sALLOW_MEMORY_GROWTH=1 -sEXPORTED_FUNCTIONS="$exported" \
  -sEXPORTED_RUNTIME_METHODS=HEAPU8,HEAPF32,HEAPU32,HEAPF64 --no-entry
echo "web/build.sh: built $out/dcurve_wasm.mjs and dcurve_wasm.wasm"
