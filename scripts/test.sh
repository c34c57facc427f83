#!/usr/bin/env bash
# Every test: set-up, build, the linter and the formatter's check (scripts/lint.sh), then native tests (CTest/GoogleTest), JS tests in Node on the wasm builds
# (Vitest; the threaded build, then the single-threaded one) and browser tests in Debian's Chromium
# (playwright-core; the isolated app runs the threaded build, a page without isolation the other). Ends with one summary line
# "total: N passed, M failed, K skipped". Tests that need ../shared/data skip, saying why, without it.
set -uo pipefail
cd "$(dirname "$0")/.."

bash scripts/setup.sh --browser || exit 1
bash scripts/build.sh || exit 1
# Results of an earlier run must not count for a suite that fails to start this time.
rm -rf test-results
mkdir -p test-results
status=0
if [ ! -d ../shared/data ]; then
  echo "note: ../shared/data (real test meshes, kept beside the project, not in it) is absent:"
  echo "      the tests that use those meshes are skipped; everything else runs."
fi

echo "== lint (ESLint over the JavaScript, clang-format's check over the C++: no finding allowed)"
bash scripts/lint.sh || status=1

echo "== native tests (ctest)"
ctest --test-dir build/native --output-on-failure -j 2 --timeout 600 \
  --output-junit "$PWD/test-results/ctest.xml" || status=1

echo "== JS tests (vitest, Node, the threaded build: build/wasm/node-threads)"
SD_WASM_BUILD=threads node node_modules/vitest/vitest.mjs run --config tests/js/vitest.config.js \
  --reporter=default --reporter=json --outputFile.json=test-results/vitest.json || status=1

echo "== JS tests again on the single-threaded build (build/wasm: what pages without isolation load)"
SD_WASM_BUILD=single node node_modules/vitest/vitest.mjs run --config tests/js/vitest.config.js \
  --reporter=dot --reporter=json --outputFile.json=test-results/vitest-single.json || status=1

echo "== browser tests (Chromium)"
node tests/e2e/run.mjs --json test-results/e2e.json || status=1

node scripts/lib/test_summary.mjs test-results || status=1
exit $status
