#!/usr/bin/env bash
# Fuzz with libFuzzer (clang, ASan + UBSan) for a bounded time.
#   scripts/fuzz.sh [SECONDS=60] [BUILD_DIR=build-fuzz] [TARGET=decoder|reader]
# decoder: the runtime decoder, seeded with the test vectors in format_spec/test_vectors.
# reader: the encoder's input readers (OBJ/OFF/PLY text and binary, glTF, PC2, MDD), seeded
# with tests/fuzz/reader_seeds. Findings (crash-*, leak-*, timeout-*) are written to
# BUILD_DIR/fuzz-findings; exit status is non-zero when there is one.
set -euo pipefail
seconds="${1:-60}"
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${2:-$src/build-fuzz}"
target="${3:-decoder}"
case "$target" in
  decoder) seeds=("$src"/format_spec/test_vectors/*.dcrv) ;;
  reader) seeds=("$src"/tests/fuzz/reader_seeds/*) ;;
  *) echo "fuzz.sh: unknown target $target (decoder or reader)" >&2; exit 2 ;;
esac
CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDCURVE_DECODER_ONLY=ON -DDCURVE_FUZZ=ON > "$build.cmake.log"
nice make -C "$build" -j2 "${target}_fuzz" > "$build.make.log"
corpus="$build/fuzz-corpus-$target"
findings="$build/fuzz-findings"
mkdir -p "$corpus" "$findings"
cp "${seeds[@]}" "$corpus"/ 2>/dev/null || true
exec "$build/tests/fuzz/${target}_fuzz" "$corpus" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix="$findings/$target-" -print_final_stats=1
