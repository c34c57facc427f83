#!/usr/bin/env bash
# Installs what is missing, builds what is stale and serves the app (with the default example) at
# http://127.0.0.1:5173 (PORT overrides). Stop with Ctrl-C.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh --wasm
port="${PORT:-5173}"
echo "start: serving the app at http://127.0.0.1:${port}/"
exec node node_modules/vite/bin/vite.js --config web/vite.config.js --host 127.0.0.1 --port "$port" --strictPort
