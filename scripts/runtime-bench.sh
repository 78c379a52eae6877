#!/usr/bin/env bash
# The runtime benchmark of the streaming decoder (decoder/README.md): encodes horse-gallop
# (corpus-ext) and a 600-frame rope-small clip at 1e-3 with each profile (small: format 3,
# fast: format 4), then runs build/bench/runtime_bench on the four files in one run: open,
# open + middle frame, open + every frame, the steady frame and a seek, memory, beside
# libdraco decoding the same frames and a memcpy of them (medians of 9 runs each). Files go to
# out/runtime/ and are reused.
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
[ -d "$dir/rope-small-600" ] || "$dcurve" simulate --scene rope-small --frames 600 -o "$dir/rope-small-600"
# Each clip twice: the default profile (format 3) and --profile fast (format 4).
files=()
encode() {  # encode SOURCE NAME PROFILE
  local target="$dir/$2-$3.dcrv"
  [ -f "$target" ] || "$dcurve" encode "$1" -o "$target" --tolerance 1e-3 --profile "$3" --force -q
  files+=("$target")
}
for profile in small fast; do
  [ -d "$corpus/horse-gallop" ] && encode "$corpus/horse-gallop" horse-gallop "$profile"
  encode "$dir/rope-small-600" rope-small-600 "$profile"
done
[ -d "$corpus/horse-gallop" ] || echo "runtime-bench: $corpus/horse-gallop not found; the rope clip alone" >&2
build/bench/runtime_bench "${files[@]}"
