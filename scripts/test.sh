#!/usr/bin/env bash
# The test command: installs dependencies, builds and installs with the README's own commands
# (Release, no unity batches), runs every test with ctest (the Python module's pytest and the
# Blender add-on's headless test among them), checks the installed add-on in Blender, builds the decoder-only variant,
# builds the WebAssembly decoder and runs its Node and headless-Chromium tests (web/test.sh),
# then does the same under AddressSanitizer + UndefinedBehaviorSanitizer (clang), then fuzzes the
# decoder and the input readers side by side for a bounded time each when the fuzz script
# exists. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

# Each phase prints the seconds since the start: CI's budget is 15 minutes for the whole run.
phase() { echo "== [${SECONDS}s] $*"; }

scripts/install-deps.sh

phase "The README's build and install, then the tests"
# Exactly the commands of README.md's "Build and install" block, read from the README (one file
# per compile: no unity batches, so a source that leans on a neighbour's includes fails here),
# with HOME in a scratch folder so its `--prefix ~/.local` stays out of the user's home.
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
readme_build=$(sed -n '/^## Build and install/,/^## /p' README.md | sed -n '/^```sh$/,/^```$/p' | grep -v '^```')
[ -n "$readme_build" ] || { echo "test.sh: no Build and install block in README.md" >&2; exit 1; }
# A build folder left configured with unity batches by an older test.sh keeps them: clear that.
if grep -qs '^CMAKE_UNITY_BUILD:BOOL=ON' build/CMakeCache.txt; then cmake -S . -B build -DCMAKE_UNITY_BUILD=OFF >/dev/null; fi
# Ninja as the generator of a new build folder (CMAKE_GENERATOR; a folder already configured
# keeps its own): the same commands, flags and one compile per file as with make, but make
# finishes each library before it starts the next target's files, which left a core idle at
# every one of the dependency chain's steps (codec, decoder, encoder, corpus, then the programs).
HOME="$scratch" CMAKE_GENERATOR=Ninja bash -euo pipefail -c "$readme_build"
[ -x "$scratch/.local/bin/dcurve" ] || { echo "test.sh: the README's install put no bin/dcurve in its prefix" >&2; exit 1; }
ctest --test-dir build --output-on-failure -j"$jobs"

phase "The installed Blender add-on"
# ctest ran the module's and the add-on's tests on the build tree (python_module,
# blender_addon) and the README's block imported the installed module; this installs the
# add-on's zip as a user would, in headless Blender, and checks it loads the module it ships.
HOME="$scratch" blender -b --factory-startup --python-exit-code 1 --python blender/tests/check_install.py -- \
  "$scratch/.local/share/dcurve/blender/io_scene_dcurve.zip" >"$scratch/blender-install.log" 2>&1 ||
  { cat "$scratch/blender-install.log" >&2; echo "test.sh: the installed add-on does not load" >&2; exit 1; }

phase "Decoder-only build (-DDCURVE_DECODER_ONLY=ON)"
# Unity batches: this checks the configuration (zstd alone, no encoder); the same sources
# were compiled one file each by the README's build above.
cmake -S . -B build-decoder-only -DCMAKE_BUILD_TYPE=Release -DDCURVE_DECODER_ONLY=ON -DCMAKE_UNITY_BUILD=ON >/dev/null
cmake --build build-decoder-only -j"$jobs"

phase "WebAssembly decoder: build, Node and Chromium tests"
DCURVE_WEB_REQUIRED=1 web/test.sh build

phase "ASan + UBSan build (clang) and tests (-DDCURVE_TOOLS=OFF)"
# -O1 -g1: sanitizers need no more. DCURVE_TOOLS=OFF: the libraries (codec, decoder, encoder,
# corpus) and their tests only; the dcurve program and the bench baselines are thin layers on
# them, tested in the Release run above, and compiling them (CLI11, json, Draco) took a third
# of this build. Release only, for time (each costs a minute or more under ASan): the
# whole-corpus guarantee sweeps and the tests made of several whole encodes of a scene. The
# same encoder and decoder paths run under the sanitizers in the smaller encode,
# motion-choice, residual and low-rank tests (LowRankPose.DamagedPosesAreRejected encodes a
# posed file).
release_only=(
  '^CorpusExt/Guarantee' '^Corpus/BuiltinGuarantee'
  '^MotionChoice\.PdeEncodeIsNeverLargerThanNone$' '^MotionChoice\.KeptMotionsEncodeWhereStoredCoefficientsRoundOtherwise$' '^Guarantee\.ChosenGridEncodesLikeTheSameGridGiven$'
  '^Guarantee\.PdeModelKeepsTheGuaranteeAndSmoothInBetweens$' '^LowRankPose\.TurningBodyGetsAPosedModelWithinTolerance$'
  '^Guarantee\.LowerEffortsEncodeTheGridsTheyName$' '^LowRank\.BuiltinSceneWithinToleranceEveryFrame$'
  # Processor-time bounds, which measure the Release code: the same paths run sanitized in
  # the other HostileRender tests.
  '^HostileRender\.ManyFaceGroupsWriteGltfInLinearTime$' '^HostileRender\.IncompressibleImageBytesAreNotSearchedAtLevel19$'
)
# Release only, whole files, for time (the sanitized build compiles them too: fit_core_test
# alone was the largest compile of the sanitized tests): the tests of the offline encoder's
# numerical fitting and choices, which read no file a user gives, only procedural animations
# and the trusted corpus: fit_core (encoder/fit: recovered coefficients, parameter search),
# curves, curves_cut, curves_corpus (encoder/curves: the curve partition and its quality),
# low_rank_choice (which model the rate control keeps) and sim_physics (the simulator's
# physics on built-in scenes). The code they test still runs under the sanitizers in every
# sanitized encode (each encode extracts curves, fits and chooses a model) and every
# simulate_builtin; the readers of untrusted input (encoder/io, scene files: sim_scene), the
# codec and the decoder keep all their tests here.
sanitize_skip_files='fit_core_test;curves_test;curves_cut_test;curves_corpus_test;low_rank_choice_test;sim_physics_test'
# Ninja rather than make: make finishes each library before starting the next target's
# files, so a long unity batch (the encoder's fitting code) left a core idle.
# clang rather than GCC (the Release build's): its ASan + UBSan build took 30% less CPU
# (the Eigen-heavy batches most) and its instrumented tests ran 30% faster; a second compiler
# also checks the sources, and clang's -fsanitize=undefined adds float-cast-overflow.
if grep -qs '^CMAKE_GENERATOR:INTERNAL=Unix Makefiles' build-sanitize/CMakeCache.txt ||
  { [ -f build-sanitize/CMakeCache.txt ] && ! grep -qs '^CMAKE_CXX_COMPILER:.*clang++' build-sanitize/CMakeCache.txt; }; then
  rm -rf build-sanitize
fi
CC=clang CXX=clang++ cmake -G Ninja -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DDCURVE_SANITIZE=ON -DDCURVE_TOOLS=OFF -DDCURVE_MICRO_BENCHMARKS=OFF -DCMAKE_UNITY_BUILD=ON \
  -DDCURVE_TESTS_EXCLUDE="$sanitize_skip_files" >/dev/null
cmake --build build-sanitize -j"$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs" -E "$(IFS='|'; echo "${release_only[*]}")"

if [ -x scripts/fuzz.sh ]; then
  # The two targets are built together, then fuzzed at the same time, 30 s each on a core of
  # its own (libFuzzer is single-threaded): the same fuzzing as one after the other, in half
  # the time.
  phase "Decoder and input reader fuzzing (bounded, side by side)"
  scripts/fuzz.sh 30 build-fuzz both
fi
phase "All tests passed"
