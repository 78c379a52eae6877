#!/usr/bin/env bash
# How encode time grows (issue 36): a built-in scene simulated at several frame counts and
# encoded with this tree's default options, then another scene (other vertex count) at the first
# frame count, then the first of them at 1 and at 2 threads. Prints seconds per run and the fitted
# exponent of time against frames and against vertices (least squares on log-log).
#   scripts/encode-scaling.sh [--scene S=rope] [--other-scene S=rope-small]
#                             [--frames "25 50 100 200"] [--tolerance T=1e-3]
# Work files go to out/encode-scaling/.
set -euo pipefail
cd "$(dirname "$0")/.."
scene=rope other=rope-small frame_counts="25 50 100 200" tolerance=1e-3
while [ $# -gt 0 ]; do
  case "$1" in
    --scene) scene=$2; shift 2 ;;
    --other-scene) other=$2; shift 2 ;;
    --frames) frame_counts=$2; shift 2 ;;
    --tolerance) tolerance=$2; shift 2 ;;
    *) echo "encode-scaling: unknown argument $1" >&2; exit 2 ;;
  esac
done
work=out/encode-scaling
mkdir -p "$work"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=OFF >/dev/null
cmake --build build -j"$(nproc 2>/dev/null || echo 2)" --target dcurve >/dev/null
bin=build/cli/dcurve

frames_of() {  # scene, frame count: the folder, simulated once
  local dir="$work/$1-$2"
  [ -d "$dir" ] || "$bin" simulate --scene "$1" --frames "$2" -o "$dir" -q
  echo "$dir"
}
json_field() { sed -n "s/.*\"$2\":\([-0-9.e+]*\).*/\1/p" "$1"; }

# Encodes a folder; prints "seconds vertices frames bytes max_error".
encode() {
  local in=$1 out=$2 t0 t1
  shift 2
  rm -f "$out.dcrv"  # a rerun replaces it (encode refuses an existing output without --force)
  t0=$(date +%s.%N)
  "$bin" encode "$in" -o "$out.dcrv" --tolerance "$tolerance" --json -q "$@" > "$out.json"
  t1=$(date +%s.%N)
  echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') $(json_field "$out.json" vertices)" \
    "$(json_field "$out.json" frames) $(json_field "$out.json" bytes) $(json_field "$out.json" max_error)"
}

# Least-squares slope of log(y) against log(x) over "x y" lines on stdin.
slope() {
  awk '{ x = log($1); y = log($2); n++; sx += x; sy += y; sxx += x * x; sxy += x * y }
       END { if (n < 2 || n * sxx == sx * sx) print "n/a"; else printf "%.2f", (n * sxy - sx * sy) / (n * sxx - sx * sx) }'
}

echo "encode time against frames: $scene, tolerance $tolerance, $(nproc) cores, $(git rev-parse --short HEAD)"
rows="" first_row=""
for F in $frame_counts; do
  read -r s v f b e < <(encode "$(frames_of "$scene" "$F")" "$work/$scene-$F")
  [ -n "$first_row" ] || first_row="$v $s"
  printf "  %-12s %5d frames %7d vertices  %8.1f s  %9.0f vertex-frames/s  %8d B  max error %.3g\n" \
    "$scene" "$f" "$v" "$s" "$(awk -v v="$v" -v f="$f" -v s="$s" 'BEGIN { print v * f / s }')" "$b" "$e"
  rows+="$f $s"$'\n'
done
echo "  exponent of time against frames: $(printf "%s" "$rows" | slope)"

first=${frame_counts%% *}
echo "encode time against vertices: $other and $scene (above) at $first frames"
read -r s v f b e < <(encode "$(frames_of "$other" "$first")" "$work/$other-$first")
printf "  %-12s %5d frames %7d vertices  %8.1f s  %8d B\n" "$other" "$f" "$v" "$s" "$b"
echo "  exponent of time against vertices: $(printf "%s\n%s\n" "$v $s" "$first_row" | slope)"

echo "threads: $scene at $first frames"
read -r s1 _ _ b1 _ < <(encode "$(frames_of "$scene" "$first")" "$work/$scene-t1" --threads 1)
read -r s2 _ _ b2 _ < <(encode "$(frames_of "$scene" "$first")" "$work/$scene-t2" --threads 2)
same=$(cmp -s "$work/$scene-t1.dcrv" "$work/$scene-t2.dcrv" && echo "identical files" || echo "FILES DIFFER")
printf "  1 thread %.1f s, 2 threads %.1f s: %.2fx; %s (%d B)\n" "$s1" "$s2" "$(awk -v a="$s1" -v b="$s2" 'BEGIN { print a / b }')" "$same" "$b1"
[ "$same" = "identical files" ]
