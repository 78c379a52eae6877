#!/usr/bin/env bash
# The web decoder's checks: builds the wasm (web/build.sh), then runs the Node tests (test
# vectors, malformed files, the three.js loader, the TypeScript declarations) and the
# headless-Chromium viewer test, and type-checks the declarations (tsc, when installed).
# The browser test needs the native build: build/cli/dcurve and build/web/dcurve_web_native
# (BUILD_DIR, default build). Usage: web/test.sh [BUILD_DIR]
set -euo pipefail
web=$(cd "$(dirname "$0")" && pwd)
build=$(cd "${1:-$web/../build}" && pwd)

"$web/build.sh"
if [ ! -f "$web/build/dcurve_wasm.wasm" ]; then
  echo "web/test.sh: no WebAssembly build (see above); web tests skipped" >&2
  exit 0
fi
[ -d "$web/node_modules/three" ] || (cd "$web" && npm ci --no-audit --no-fund)
cd "$web"
# typescript is a devDependency, but a node_modules installed before it was added lacks it.
if [ -x node_modules/.bin/tsc ]; then
  node_modules/.bin/tsc --noEmit -p tsconfig.json
  echo "web/test.sh: tsc --noEmit: the declarations type-check"
else
  echo "web/test.sh: typescript not installed (npm ci in web/); tsc check skipped" >&2
fi
DCURVE="$build/cli/dcurve" DCURVE_WEB_NATIVE="$build/web/dcurve_web_native" node --test test/*.test.mjs
