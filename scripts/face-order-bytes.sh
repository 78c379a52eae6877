#!/usr/bin/env bash
# What keeping the input's exact index buffer costs: each input encoded with the default
# face layout (triangles in the face coder's order) and with --keep-face-order, back to back,
# at one tolerance. Prints name, both file sizes and their ratio; exits non-zero if the
# default is ever larger.
#   scripts/face-order-bytes.sh [--corpus DIR=../shared/corpus-ext] [--dcurve BIN=build/cli/dcurve]
#                               [--tolerance T=1e-3] [SEQUENCE...]
# SEQUENCE: a corpus-ext folder name (default: the five sequences). Files go to out/face-order/.
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=../shared/corpus-ext dcurve=build/cli/dcurve tolerance=1e-3
inputs=()
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus=$2; shift 2 ;;
    --dcurve) dcurve=$2; shift 2 ;;
    --tolerance) tolerance=$2; shift 2 ;;
    -*) echo "face-order-bytes: unknown option $1" >&2; exit 2 ;;
    *) inputs+=("$1"); shift ;;
  esac
done
[ ${#inputs[@]} -gt 0 ] || inputs=(horse-gallop chicken-crossing cloth-sphere elastic-cow crane)
[ -x "$dcurve" ] || { echo "face-order-bytes: $dcurve not found: build the dcurve target first" >&2; exit 1; }
work=out/face-order
mkdir -p "$work"

json_field() { sed -n "s/.*\"$2\":\([0-9]*\).*/\1/p" "$1"; }

# Encodes $1 with options $3 into $work/$2.dcrv; prints its "bytes connectivity_bytes".
encode() {
  # shellcheck disable=SC2086
  "$dcurve" encode "$corpus/$1" -o "$work/$2.dcrv" --tolerance "$tolerance" --json -q --force $3 > "$work/$2.json"
  echo "$(json_field "$work/$2.json" bytes) $(json_field "$work/$2.json" connectivity_bytes)"
}

echo "tolerance $tolerance; bytes of the whole file (FACE section in parentheses)"
printf '| %s | %s | %s | %s |\n|---|---|---|---|\n' sequence default --keep-face-order "default / keep"
larger=0
for name in "${inputs[@]}"; do
  read -r db dc < <(encode "$name" "$name-default" "")
  read -r kb kc < <(encode "$name" "$name-keep" --keep-face-order)
  printf '| %s | %d (%d) | %d (%d) | %s |\n' "$name" "$db" "$dc" "$kb" "$kc" "$(awk -v a="$db" -v b="$kb" 'BEGIN { printf "%.3f", a / b }')"
  [ "$db" -le "$kb" ] || larger=1
done
[ "$larger" = 0 ] || { echo "face-order-bytes: the default is larger on some input" >&2; exit 1; }
