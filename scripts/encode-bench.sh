#!/usr/bin/env bash
# Encoder speed and size against a baseline encoder built from an older commit, in one run on
# one machine (issue 36): for each input, the baseline's `dcurve encode` and this tree's, back
# to back, at the same tolerance; wall seconds, bytes and the max error each reports (measured
# by decoding its own file). Prints one row per input and the totals.
#   scripts/encode-bench.sh [--baseline REV=25b4dd9] [--corpus DIR=../shared/corpus-ext]
#                           [--tolerance T=1e-3] [--args "NEW ENCODER OPTIONS"] [INPUT...]
# INPUT: a built-in scene name (simulated once with this tree's dcurve; frames are
# deterministic) or a corpus-ext sequence name. Default: the five built-in scenes, the five
# corpus-ext sequences and the full-size rope. Work files go to out/encode-bench/.
set -euo pipefail
cd "$(dirname "$0")/.."
baseline=25b4dd9 corpus=../shared/corpus-ext tolerance=1e-3 new_args=""
inputs=()
while [ $# -gt 0 ]; do
  case "$1" in
    --baseline) baseline=$2; shift 2 ;;
    --corpus) corpus=$2; shift 2 ;;
    --tolerance) tolerance=$2; shift 2 ;;
    --args) new_args=$2; shift 2 ;;
    -*) echo "encode-bench: unknown option $1" >&2; exit 2 ;;
    *) inputs+=("$1"); shift ;;
  esac
done
[ ${#inputs[@]} -gt 0 ] || inputs=(rope-small cantilever neck blob sheet horse-gallop chicken-crossing elastic-cow
  cloth-sphere crane rope)
jobs=$(nproc 2>/dev/null || echo 2)
work=out/encode-bench
mkdir -p "$work/frames" "$work/files"

# This tree's encoder, and the baseline's from its own source tree (git archive: no worktree).
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=OFF >/dev/null
cmake --build build -j"$jobs" --target dcurve >/dev/null
new=build/cli/dcurve
rev=$(git rev-parse --short "$baseline")
base_src="$work/baseline-$rev"
if [ ! -x "$base_src/build/cli/dcurve" ]; then
  rm -rf "$base_src" && mkdir -p "$base_src"
  git archive "$rev" | tar -x -C "$base_src"
  cmake -S "$base_src" -B "$base_src/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON \
    -DDCURVE_MICRO_BENCHMARKS=OFF >/dev/null
  cmake --build "$base_src/build" -j"$jobs" --target dcurve >/dev/null
fi
base="$base_src/build/cli/dcurve"

# The frames of an input: a corpus-ext folder, or a built-in scene simulated once.
frames_of() {
  if [ -d "$corpus/$1" ]; then echo "$corpus/$1"; return; fi
  [ -d "$work/frames/$1" ] || "$new" simulate --scene "$1" -o "$work/frames/$1" -q
  echo "$work/frames/$1"
}

json_field() { sed -n "s/.*\"$2\":\([-0-9.e+]*\).*/\1/p" "$1"; }
now() { date +%s.%N; }

# Runs one encoder (stderr, its progress, to a log); prints "seconds bytes max_error".
run() {
  local bin=$1 in=$2 out=$3 args=$4 t0 t1
  rm -f "$out.dcrv"  # a rerun replaces it (encode refuses an existing output without --force)
  t0=$(now)
  # shellcheck disable=SC2086
  "$bin" encode "$in" -o "$out.dcrv" --tolerance "$tolerance" --json $args > "$out.json" 2> "$out.log"
  t1=$(now)
  echo "$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }') $(json_field "$out.json" bytes) $(json_field "$out.json" max_error)"
}

echo "baseline $rev ($base) against $(git rev-parse --short HEAD)$(git diff --quiet HEAD || echo +changes)" \
  "${new_args:+with $new_args}; tolerance $tolerance; $(nproc) cores"
rows="$work/rows.txt"
: > "$rows"
for name in "${inputs[@]}"; do
  in=$(frames_of "$name")
  read -r bs bb be < <(run "$base" "$in" "$work/files/$name-base" "")
  read -r ns nb ne < <(run "$new" "$in" "$work/files/$name-new" "$new_args")
  echo "$name $bs $ns $bb $nb $be $ne" | tee -a "$rows" >/dev/null
  awk -v tol="$tolerance" '{ printf "%-17s base %7.1f s  new %7.1f s  %6.2fx   base %8d B  new %8d B  %.4f   max error %.3g / %.3g%s\n",
    $1, $2, $3, $2 / $3, $4, $5, $5 / $4, $6, $7, ($7 > tol ? "  OVER THE TOLERANCE" : "") }' <<< "$name $bs $ns $bb $nb $be $ne"
done
awk -v tol="$tolerance" '{ b += $2; n += $3; r = $5 / $4; if (r > worst) worst = r; if ($7 > tol) over++ }
  END { printf "total: baseline %.1f s, new %.1f s, %.2fx faster; largest bytes ratio %.4f; %d over the tolerance\n",
        b, n, b / n, worst, over; exit over > 0 }' "$rows"
