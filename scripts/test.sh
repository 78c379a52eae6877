#!/usr/bin/env bash
# The test command: installs dependencies, builds (Release), runs every test with ctest,
# then does the same under AddressSanitizer + UndefinedBehaviorSanitizer, then fuzzes the
# decoder for a bounded time when the fuzz script exists. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

scripts/install-deps.sh

echo "== Release build and tests"
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

echo "== ASan + UBSan build and tests"
# -O1 -g1: sanitizers need no more, and the build stays a few minutes on 2 cores.
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
  -DDCURVE_SANITIZE=ON -DDCURVE_MICRO_BENCHMARKS=OFF >/dev/null
cmake --build build-sanitize -j"$jobs"
# The install test links an outside project against the installed libraries, which the
# sanitizer runtime would have to follow; the Release run covers it. The whole-corpus
# guarantee sweeps (minutes under ASan) run in Release only: the same encoder and decoder
# paths run under the sanitizers in the smaller encode, residual and low-rank tests.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-sanitize --output-on-failure -j"$jobs" \
  -E 'install_consumer|^CorpusExt/Guarantee|^Corpus/BuiltinGuarantee'

if [ -x scripts/fuzz.sh ]; then
  echo "== Decoder fuzzing (bounded)"
  scripts/fuzz.sh 60
fi
echo "== All tests passed"
