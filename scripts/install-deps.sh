#!/usr/bin/env bash
# Installs the Debian packages dcurve builds against (the Python module's too: pybind11, numpy
# and pytest for Debian's python3, Blender 3.4 for the add-on's test), then Node and the npm
# packages of the interoperability tests (tests/interop: glTF-Transform and the Khronos glTF validator) and of
# the web decoder (web/: three, fzstd, playwright-core; Emscripten and Chromium from Debian).
# Idempotent: does nothing when all are present. Quiet on success; on failure prints the
# installer's output and exits non-zero.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libdraco-dev draco libopenmesh-dev libtet1.5-dev libzstd-dev
  libgtest-dev libgmock-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev
  libmeshoptimizer-dev libhtscodecs-dev clang libclang-rt-14-dev libtinygltf-dev
  emscripten chromium
  python3-dev pybind11-dev python3-numpy python3-pytest blender
)
# Node from Debian unless a node and npm are already on the PATH (e.g. NodeSource's nodejs,
# which bundles npm and conflicts with Debian's npm package).
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

root=$(cd "$(dirname "$0")/.." && pwd)
# npm ci in folder $1 unless the packages $2... are there.
npm_ci() {
  local dir=$1 npm_log p
  shift
  for p in "$@"; do [ -d "$dir/node_modules/$p" ] || break; done
  [ -d "$dir/node_modules/$p" ] && return 0
  npm_log=$(mktemp)
  echo "install-deps: npm ci in ${dir#"$root"/}" >&2
  if ! (cd "$dir" && npm ci --no-audit --no-fund) >"$npm_log" 2>&1; then
    cat "$npm_log" >&2
    rm -f "$npm_log"
    echo "install-deps: npm ci failed in $dir" >&2
    exit 1
  fi
  rm -f "$npm_log"
}
install_npm_packages() {
  npm_ci "$root/tests/interop" @gltf-transform/core gltf-validator
  npm_ci "$root/web" three fzstd playwright-core typescript @types/three
}

if [ ${#missing[@]} -eq 0 ]; then
  install_npm_packages
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
log=$(mktemp)
trap 'rm -f "$log"' EXIT
echo "install-deps: installing ${missing[*]}" >&2
if ! { $sudo apt-get update -q && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"; } >"$log" 2>&1; then
  cat "$log" >&2
  echo "install-deps: apt-get failed for: ${missing[*]}" >&2
  exit 1
fi
install_npm_packages
