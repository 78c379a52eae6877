#!/usr/bin/env bash
# Fuzz the runtime decoder with libFuzzer (clang, ASan + UBSan) for a bounded time.
#   scripts/fuzz.sh [SECONDS=60] [BUILD_DIR=build-fuzz]
# Seeds: the test vectors in format_spec/test_vectors. Findings (crash-*, leak-*, timeout-*)
# are written to BUILD_DIR/fuzz-findings; exit status is non-zero when there is one.
set -euo pipefail
seconds="${1:-60}"
src="$(cd "$(dirname "$0")/.." && pwd)"
build="${2:-$src/build-fuzz}"
CC=clang CXX=clang++ cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DDCURVE_DECODER_ONLY=ON -DDCURVE_FUZZ=ON > "$build.cmake.log"
nice make -C "$build" -j2 decoder_fuzz > "$build.make.log"
corpus="$build/fuzz-corpus"
findings="$build/fuzz-findings"
mkdir -p "$corpus" "$findings"
cp "$src"/format_spec/test_vectors/*.dcrv "$corpus"/ 2>/dev/null || true
exec "$build/tests/fuzz/decoder_fuzz" "$corpus" -max_total_time="$seconds" -timeout=10 \
  -rss_limit_mb=2048 -malloc_limit_mb=1024 -artifact_prefix="$findings/" -print_final_stats=1
