#!/usr/bin/env bash
# The runtime benchmark of the streaming decoder (decoder/README.md): encodes horse-gallop
# (corpus-ext) and a 600-frame rope-small clip at 1e-3, then runs build/bench/runtime_bench
# on both in one run: open, open + middle frame, open + every frame, memory, beside libdraco
# decoding the same frames and a memcpy of them. Files go to out/runtime/ and are reused.
#   scripts/runtime-bench.sh [CORPUS_EXT=../shared/corpus-ext]
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=${1:-../shared/corpus-ext}
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=OFF >/dev/null
cmake --build build -j"$jobs" --target dcurve runtime_bench
dcurve=build/cli/dcurve
dir=out/runtime
mkdir -p "$dir"
if [ ! -f "$dir/rope-small-600.dcrv" ]; then
  [ -d "$dir/rope-small-600" ] || "$dcurve" simulate --scene rope-small --frames 600 -o "$dir/rope-small-600"
  "$dcurve" encode "$dir/rope-small-600" -o "$dir/rope-small-600.dcrv" --tolerance 1e-3 --force
fi
files=("$dir/rope-small-600.dcrv")
if [ -d "$corpus/horse-gallop" ]; then
  [ -f "$dir/horse-gallop.dcrv" ] || "$dcurve" encode "$corpus/horse-gallop" -o "$dir/horse-gallop.dcrv" --tolerance 1e-3
  files=("$dir/horse-gallop.dcrv" "${files[@]}")
else
  echo "runtime-bench: $corpus/horse-gallop not found; the rope clip alone" >&2
fi
build/bench/runtime_bench "${files[@]}"
