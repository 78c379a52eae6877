#!/usr/bin/env bash
# Fuzz with libFuzzer (clang, ASan + UBSan) for a bounded time.
#   scripts/fuzz.sh [SECONDS=60] [BUILD_DIR=build-fuzz] [TARGET=decoder|reader|both]
# decoder: the runtime decoder, seeded with the test vectors in format_spec/test_vectors and
# tests/fuzz/decoder_seeds (REND with groups, PLAC, MATL with an image).
# reader: the encoder's input readers (OBJ/OFF/PLY text and binary, glTF, PC2, MDD), seeded
# with tests/fuzz/reader_seeds. both: builds the two targets together, then runs the two
# fuzzers at the same time for SECONDS each (one core each; libFuzzer runs one thread), each
# one's output printed whole when it ends. Findings (crash-*, leak-*, timeout-*) are written
# to BUILD_DIR/fuzz-findings; exit status is non-zero when there is one.
set -euo pipefail
seconds="${1:-60}"
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${2:-$src/build-fuzz}"
target="${3:-decoder}"
case "$target" in
  decoder | reader) targets=("$target") ;;
  both) targets=(decoder reader) ;;
  *) echo "fuzz.sh: unknown target $target (decoder, reader or both)" >&2; exit 2 ;;
esac
# Ninja and unity batches: the instrumented compile parses the shared headers (tinygltf,
# OpenMesh) once per batch, half the CPU of one compile per file, and builds both targets at
# once (make built one target after the other). The instrumentation is the same per function.
if grep -qs '^CMAKE_GENERATOR:INTERNAL=Unix Makefiles' "$build/CMakeCache.txt"; then rm -rf "$build"; fi
CC=clang CXX=clang++ cmake -G Ninja -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDCURVE_DECODER_ONLY=ON -DDCURVE_FUZZ=ON -DCMAKE_UNITY_BUILD=ON > "$build.cmake.log"
nice ninja -C "$build" -j2 "${targets[@]/%/_fuzz}" > "$build.build.log" || { cat "$build.build.log" >&2; exit 1; }
findings="$build/fuzz-findings"
mkdir -p "$findings"
# Runs one target's fuzzer for $seconds.
fuzz() {
  local t=$1 corpus="$build/fuzz-corpus-$1" seeds
  case "$t" in
    decoder) seeds=("$src"/format_spec/test_vectors/*.dcrv "$src"/tests/fuzz/decoder_seeds/*.dcrv) ;;
    reader) seeds=("$src"/tests/fuzz/reader_seeds/*) ;;
  esac
  mkdir -p "$corpus"
  cp "${seeds[@]}" "$corpus"/ 2>/dev/null || true
  "$build/tests/fuzz/${t}_fuzz" "$corpus" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix="$findings/$t-" -print_final_stats=1
}
if [ ${#targets[@]} -eq 1 ]; then
  fuzz "$target"
  exit
fi
pids=()
for t in "${targets[@]}"; do
  fuzz "$t" > "$build/fuzz-$t.log" 2>&1 &
  pids+=($!)
done
status=0
for i in "${!targets[@]}"; do
  rc=0
  wait "${pids[$i]}" || rc=$?
  echo "-- fuzz.sh: ${targets[$i]} (exit $rc)"
  cat "$build/fuzz-${targets[$i]}.log"
  [ $rc -eq 0 ] || status=$rc
done
exit $status
