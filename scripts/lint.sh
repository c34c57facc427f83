#!/usr/bin/env bash
# The linter and the formatter's check, changing nothing: ESLint (eslint.config.js) over the JavaScript, then
# clang-format (.clang-format) over the C++ of cpp/, tests/cpp and tests/fuzz, failing on any file it would
# change. `bash scripts/lint.sh --fix` applies both instead (ESLint's fixes, clang-format -i).
# Usage: bash scripts/lint.sh [--fix]
set -euo pipefail
cd "$(dirname "$0")/.."

fix=0
case "${1:-}" in
  "") ;;
  --fix) fix=1 ;;
  *) echo "usage: bash scripts/lint.sh [--fix]" >&2; exit 2 ;;
esac
if [ ! -f node_modules/eslint/bin/eslint.js ]; then
  echo "lint: node_modules/eslint is missing: run 'bash scripts/setup.sh' (npm ci) first" >&2
  exit 1
fi
if ! command -v clang-format >/dev/null; then
  echo "lint: clang-format is missing: run 'bash scripts/setup.sh' (Debian package clang-format)" >&2
  exit 1
fi

status=0
echo "lint: eslint"
if [ "$fix" = 1 ]; then
  node node_modules/eslint/bin/eslint.js --fix . || status=1
else
  node node_modules/eslint/bin/eslint.js --max-warnings 0 . || status=1
fi

echo "lint: clang-format"
mapfile -d '' sources < <(find cpp tests/cpp tests/fuzz -type f \( -name '*.cpp' -o -name '*.h' \) -print0 | sort -z)
if [ "$fix" = 1 ]; then
  clang-format -i "${sources[@]}" || status=1
else
  clang-format --dry-run --Werror "${sources[@]}" 2>/tmp/subspace-deform-clang-format.log || {
    grep -c 'error:' /tmp/subspace-deform-clang-format.log | xargs -I{} echo "lint: clang-format would change {} places (first ones below; 'bash scripts/lint.sh --fix' formats)" >&2
    head -40 /tmp/subspace-deform-clang-format.log >&2
    status=1
  }
fi
exit $status
