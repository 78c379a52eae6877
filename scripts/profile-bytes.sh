#!/usr/bin/env bash
# Bytes of the two profiles side by side at 1e-3: --profile small (format 3.2) and --profile
# fast (format 4.0) of this tree's dcurve, on the five built-in scenes (simulated at their
# default length) and the five corpus-ext sequences, one run. Prints a markdown table of the
# bytes, their ratio, each file's max error (from decoding it) and the encode seconds.
#   scripts/profile-bytes.sh [--corpus DIR=../shared/corpus-ext] [--dcurve BIN=build/cli/dcurve]
# Files go to out/profile-bytes/ and are reused.
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=../shared/corpus-ext dcurve=build/cli/dcurve
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus=$2; shift 2 ;;
    --dcurve) dcurve=$2; shift 2 ;;
    *) echo "profile-bytes: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -x "$dcurve" ] || { echo "profile-bytes: $dcurve not found: build the dcurve target first" >&2; exit 1; }
work=out/profile-bytes
mkdir -p "$work"
inputs=()
for scene in rope-small cantilever neck blob sheet; do
  [ -d "$work/$scene" ] || "$dcurve" simulate --scene "$scene" -o "$work/$scene/" -q
  inputs+=("$work/$scene")
done
for s in horse-gallop chicken-crossing cloth-sphere elastic-cow crane; do inputs+=("$corpus/$s"); done

echo "| input | small (3.2) bytes | fast (4.0) bytes | fast / small | max error small / fast | encode s small / fast |"
echo "|---|---|---|---|---|---|"
for input in "${inputs[@]}"; do
  name=$(basename "$input")
  for profile in small fast; do
    json="$work/$name-$profile.json"
    [ -s "$json" ] || "$dcurve" encode "$input" -o "$work/$name-$profile.dcrv" --tolerance 1e-3 \
      --profile "$profile" --force -q --json > "$json"
  done
  python3 - "$name" "$work/$name-small.json" "$work/$name-fast.json" <<'PY'
import json, sys
name, small, fast = sys.argv[1], json.load(open(sys.argv[2])), json.load(open(sys.argv[3]))
print(f"| {name} | {small['bytes']:,} | {fast['bytes']:,} | {fast['bytes'] / small['bytes']:.2f} | "
      f"{small['max_error']:.6f} / {fast['max_error']:.6f} | {small['encode_seconds']:.0f} / {fast['encode_seconds']:.0f} |")
PY
done
