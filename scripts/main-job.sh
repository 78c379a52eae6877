#!/usr/bin/env bash
# The main job, end to end on the built-in default scene: simulate -> encode -> decode ->
# bench, ending with the comparison table. Outputs go to out/. Parts not built yet say so.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
scene=${DCURVE_SCENE:-rope-small}
tolerance=${DCURVE_TOLERANCE:-1e-3}

scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=OFF >/dev/null
cmake --build build -j"$jobs" --target dcurve
dcurve=build/cli/dcurve
rm -rf out && mkdir -p out

echo "== simulate: built-in scene '$scene' -> out/frames"
if ! "$dcurve" simulate --scene "$scene" -o out/frames; then
  echo "simulate failed or is not built yet; the rest of the job needs its frames" >&2
  exit 1
fi
echo "== encode: out/frames -> out/$scene.dcrv (tolerance $tolerance of the rest-pose diagonal)"
"$dcurve" encode out/frames -o "out/$scene.dcrv" --tolerance "$tolerance"
"$dcurve" info "out/$scene.dcrv"
echo "== decode: out/$scene.dcrv -> out/decoded"
"$dcurve" decode "out/$scene.dcrv" -o out/decoded
echo "== bench: dcurve against Draco and the other baselines"
"$dcurve" bench out/frames --tolerance "$tolerance" --plot out/rate_distortion.svg
