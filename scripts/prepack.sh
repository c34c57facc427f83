#!/usr/bin/env bash
# npm pack / npm publish run this first (package.json "prepack"): it builds what the package ships and is
# missing -- the wasm modules, their glue and the generated schema (scripts/build.sh --wasm, which also builds
# the C++ core) -- and always regenerates the TypeScript declarations (build/types), which take seconds.
# Present wasm files are not rebuilt: run scripts/build.sh first to pick up C++ changes.
set -euo pipefail
cd "$(dirname "$0")/.."

# The files package.json "files" names from build/wasm: what web/lib/load.js (browsers: the single build, bundled,
# and the threaded one, which a page copies to threads/ at its site's root: docs/embed.md) and web/lib/node.js
# (Node: node-threads' glue by default, with threads/' .wasm, the same bytes; the single build with build: 'single')
# load, and the schema the library imports.
needed=(
  build/wasm/solver_schema.js
  build/wasm/subspace_deform.js
  build/wasm/subspace_deform.wasm
  build/wasm/threads/subspace_deform.js
  build/wasm/threads/subspace_deform.wasm
  build/wasm/threads/subspace_deform.worker.js
  build/wasm/node-threads/package.json
  build/wasm/node-threads/subspace_deform.js
  build/wasm/node-threads/subspace_deform.worker.js
)
missing=()
for file in "${needed[@]}"; do [ -f "$file" ] || missing+=("$file"); done
if [ ${#missing[@]} -gt 0 ]; then
  echo "prepack: missing ${missing[*]}: building (scripts/build.sh --wasm)" >&2
  bash scripts/build.sh --wasm >&2  # stdout is npm pack --json's
else
  if [ ! -f node_modules/typescript/bin/tsc ]; then
    echo "prepack: node_modules/typescript is missing: run 'npm ci' first" >&2
    exit 1
  fi
  echo "prepack: declarations (build/types)" >&2
  node node_modules/typescript/bin/tsc -p web/lib/tsconfig.json >&2
fi
