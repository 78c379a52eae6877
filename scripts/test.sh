#!/usr/bin/env bash
# The test command: installs dependencies, builds (Release), runs every test with ctest,
# builds the WebAssembly decoder and runs its Node and headless-Chromium tests (web/test.sh),
# then does the same under AddressSanitizer + UndefinedBehaviorSanitizer, then fuzzes the
# decoder and the input readers for a bounded time each when the fuzz script exists. Exits
# non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scripts/install-deps.sh

echo "== Release build and tests"
# Unity builds: a clean build on 2 cores takes about 60 % of the time of one file per compile.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

echo "== WebAssembly decoder: build, Node and Chromium tests"
DCURVE_WEB_REQUIRED=1 web/test.sh build

echo "== ASan + UBSan build and tests"
# -O1 -g1: sanitizers need no more. DCURVE_TOOLS=OFF: the libraries (codec, decoder, encoder,
# corpus) and their tests only; the dcurve program and the bench baselines are thin layers on
# them, tested in the Release run above, and compiling them (CLI11, json, Draco) took a third
# of this build. Release only, for time (each costs a minute or more under ASan): the
# whole-corpus guarantee sweeps and the tests made of several whole encodes of a scene. The
# same encoder and decoder paths run under the sanitizers in the smaller encode, fit,
# motion-choice, residual and low-rank tests (LowRankPose.DamagedPosesAreRejected encodes a
# posed file).
release_only=(
  '^CorpusExt/Guarantee' '^Corpus/BuiltinGuarantee'
  '^MotionChoice\.PdeEncodeIsNeverLargerThanNone$' '^Guarantee\.ChosenGridEncodesLikeTheSameGridGiven$'
  '^Guarantee\.PdeModelKeepsTheGuaranteeAndSmoothInBetweens$' '^LowRankPose\.TurningBodyGetsAPosedModelWithinTolerance$'
  '^Guarantee\.LowerEffortsEncodeTheGridsTheyName$' '^LowRank\.BuiltinSceneWithinToleranceEveryFrame$'
)
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DDCURVE_SANITIZE=ON -DDCURVE_TOOLS=OFF -DDCURVE_MICRO_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build-sanitize -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs" -E "$(IFS='|'; echo "${release_only[*]}")"

if [ -x scripts/fuzz.sh ]; then
  echo "== Decoder fuzzing (bounded)"
  scripts/fuzz.sh 30 build-fuzz decoder
  echo "== Input reader fuzzing (bounded)"
  scripts/fuzz.sh 30 build-fuzz reader
fi
echo "== All tests passed"
