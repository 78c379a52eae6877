#!/usr/bin/env bash
# Installs the built project into a scratch prefix, builds the consumer project against it
# with find_package(dcurve), and runs it on a file the CLI encodes from two frames.
set -euo pipefail
build_dir=$1; source_dir=$2; dcurve=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build_dir" --prefix "$work/prefix" >/dev/null
cmake -S "$source_dir/tests/consumer" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build" -j2 >/dev/null
mkdir "$work/frames"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n' > "$work/frames/a.obj"
printf 'v 0 0 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n' > "$work/frames/b.obj"
"$dcurve" encode "$work/frames" -o "$work/tri.dcrv" --tolerance 1e-3 >/dev/null
"$work/build/consumer_c" "$work/tri.dcrv" | tee "$work/out.txt"
grep -q "vertices 3 frames 2 faces 1 centroid 0.3333.. 0.3333.. 0.5000" "$work/out.txt"
"$work/build/consumer_cpp" "$work/tri.dcrv"
# Linking the decoder alone must not drag in encoder dependencies.
! grep -qiE "openmesh|draco|tet|eigen" "$work/prefix/lib/cmake/dcurve/dcurveTargets.cmake"
