#!/usr/bin/env bash
# The top-level README's result tables, from one run of this tree's dcurve on its default
# settings: the built-in corpus and the five corpus-ext sequences at 1e-3 against Draco per
# frame, quantized delta and PCA (`dcurve bench`), and the sequences at 1e-2 and 1e-4 against
# quantized delta. Prints the markdown to paste; every error is measured by decoding each
# method's own bytes, and a method that misses its tolerance shows n/a. Regenerate the README
# whenever the format or an encoder default changes. Takes about an hour on 2 loaded cores.
#   scripts/readme-tables.sh [--corpus DIR=../shared/corpus-ext] [--dcurve BIN=build/cli/dcurve]
#                            [--skip-tolerances]
# Work files (the bench JSON) go to out/readme-tables/.
set -euo pipefail
cd "$(dirname "$0")/.."
corpus=../shared/corpus-ext dcurve=build/cli/dcurve tolerances=1
while [ $# -gt 0 ]; do
  case "$1" in
    --corpus) corpus=$2; shift 2 ;;
    --dcurve) dcurve=$2; shift 2 ;;
    --skip-tolerances) tolerances=0; shift ;;
    *) echo "readme-tables: unknown argument $1" >&2; exit 2 ;;
  esac
done
[ -x "$dcurve" ] || { echo "readme-tables: $dcurve not found: build the dcurve target first" >&2; exit 1; }
work=out/readme-tables
mkdir -p "$work"
sequences=()
for s in horse-gallop chicken-crossing cloth-sphere elastic-cow crane; do sequences+=("$corpus/$s"); done
methods=dcurve,draco_per_frame,quantized_delta,pca

# Progress lines go to the log, the JSON to its file.
bench() {
  local out=$1
  shift
  "$dcurve" bench "$@" --json > "$work/$out.json" 2> "$work/$out.log" ||
    { echo "readme-tables: dcurve bench $* failed, see $work/$out.log" >&2; exit 1; }
}
bench builtin --tolerance 1e-3 --methods "$methods"
bench corpus-ext "${sequences[@]}" --tolerance 1e-3 --methods "$methods"
[ "$tolerances" = 0 ] || bench tolerances "${sequences[@]}" --tolerance 1e-2 --tolerance 1e-4 --methods dcurve,quantized_delta

echo "Built-in corpus, \`dcurve bench --tolerance 1e-3\` (rope-small, cantilever, neck, blob, sheet):"
echo
node scripts/readme-tables.mjs comparison scene "$work/builtin.json"
echo
echo "External corpus (\`../shared/corpus-ext\`), \`C=../shared/corpus-ext; dcurve bench \$C/horse-gallop"
echo "\$C/chicken-crossing \$C/cloth-sphere \$C/elastic-cow \$C/crane --tolerance 1e-3\`:"
echo
node scripts/readme-tables.mjs comparison sequence "$work/corpus-ext.json"
if [ "$tolerances" = 1 ]; then
  echo
  echo "The same sequences at 1e-2 and 1e-4 (\`... --tolerance 1e-2 --tolerance 1e-4 --methods"
  echo "dcurve,quantized_delta\`), dcurve's bytes and their ratio to quantized delta's:"
  echo
  node scripts/readme-tables.mjs tolerances "$work/tolerances.json"
fi
