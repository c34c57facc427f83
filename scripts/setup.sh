#!/usr/bin/env bash
# Installs what the project needs and is missing, on Debian 12:
#   Debian packages (as root: apt-get; otherwise prints the exact command to run) and npm packages (npm ci).
# Usage: bash scripts/setup.sh [--browser]   (--browser also requires Chromium, for the browser tests)
set -euo pipefail
cd "$(dirname "$0")/.."

want_browser=0
[ "${1:-}" = "--browser" ] && want_browser=1

# package -> a file that proves it is installed
declare -A PROOF=(
  [g++]=/usr/bin/g++
  [cmake]=/usr/bin/cmake
  [libgtest-dev]=/usr/include/gtest/gtest.h
  [libeigen3-dev]=/usr/share/eigen3/cmake/Eigen3Config.cmake
  [libspectra-dev]=/usr/share/spectra/cmake/spectra-config.cmake
  [emscripten]=/usr/bin/emcc
  [clang-format]=/usr/bin/clang-format
)
[ "$want_browser" = 1 ] && PROOF[chromium]=/usr/bin/chromium

missing=()
for package in "${!PROOF[@]}"; do
  [ -e "${PROOF[$package]}" ] || missing+=("$package")
done

if [ ${#missing[@]} -gt 0 ]; then
  command="apt-get update && apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "setup: installing Debian packages: ${missing[*]}"
    DEBIAN_FRONTEND=noninteractive bash -c "$command" >/tmp/subspace-deform-apt.log 2>&1 || {
      tail -20 /tmp/subspace-deform-apt.log
      echo "setup: apt-get failed (full log: /tmp/subspace-deform-apt.log)" >&2
      exit 1
    }
  else
    echo "setup: missing Debian packages: ${missing[*]}" >&2
    echo "setup: run this as root, then try again:" >&2
    echo "  sudo sh -c '$command'" >&2
    exit 1
  fi
fi

if ! command -v node >/dev/null || [ "$(node -p 'process.versions.node.split(".")[0]')" -lt 20 ]; then
  echo "setup: Node.js 20 or newer is required (found: $(node --version 2>/dev/null || echo none))." >&2
  echo "setup: as root: apt-get install -y nodejs npm, or install Node 20 from your distribution." >&2
  exit 1
fi

# npm ci when node_modules is absent or older than the lock file.
if [ ! -f node_modules/.package-lock.json ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  echo "setup: npm ci"
  npm ci --no-audit --no-fund --loglevel=error
fi
