#!/usr/bin/env bash
# Builds what is stale: the native core + tests (build/native), the WebAssembly modules with the generated
# options schema (build/wasm) and the library's TypeScript declarations (build/types).
# CMake and make rebuild only what changed, so a second run takes seconds.
# Usage: bash scripts/build.sh [--native] [--wasm]   (default: both)
set -euo pipefail
cd "$(dirname "$0")/.."

build_native=1
build_wasm=1
if [ $# -gt 0 ]; then
  build_native=0
  build_wasm=0
  for arg in "$@"; do
    case "$arg" in
      --native) build_native=1 ;;
      --wasm) build_wasm=1 ;;
      *) echo "usage: bash scripts/build.sh [--native] [--wasm]" >&2; exit 2 ;;
    esac
  done
fi
jobs=$(nproc 2>/dev/null || echo 2)

if [ "$build_native" = 1 ]; then
  [ -f build/native/CMakeCache.txt ] || cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release >/dev/null
  echo "build: native (build/native)"
  # Progress lines are dropped; warnings and errors stay. pipefail keeps cmake's status.
  cmake --build build/native -j "$jobs" 2>&1 | { grep -vE '^\[ *[0-9]+%\]' || true; } ||
    { echo "build: native build failed" >&2; exit 1; }
fi

if [ "$build_wasm" = 1 ]; then
  # Emscripten's cache must be writable; Debian's lives under /usr/share when we are not root.
  [ -w /usr/share/emscripten/cache ] || export EM_CACHE="${EM_CACHE:-$HOME/.cache/emscripten}"
  [ -f build/wasm/CMakeCache.txt ] || emcmake cmake -S . -B build/wasm -DCMAKE_BUILD_TYPE=Release >/dev/null
  echo "build: wasm (build/wasm)"
  # Progress lines are dropped; warnings and errors stay. pipefail keeps cmake's status.
  cmake --build build/wasm -j "$jobs" 2>&1 | { grep -vE '^\[ *[0-9]+%\]' || true; } ||
    { echo "build: wasm build failed" >&2; exit 1; }
  # TypeScript declarations of the JS library from its JSDoc (package.json "types"), after the wasm build
  # because they include the generated build/wasm/solver_schema.js; any error fails the build.
  if [ ! -f node_modules/typescript/bin/tsc ]; then
    echo "build: node_modules/typescript is missing: run 'bash scripts/setup.sh' (npm ci) first" >&2
    exit 1
  fi
  echo "build: types (build/types)"
  node node_modules/typescript/bin/tsc -p web/lib/tsconfig.json || { echo "build: declarations failed" >&2; exit 1; }
fi
