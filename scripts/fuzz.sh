#!/usr/bin/env bash
# Fuzzes for a bounded time per target:
#   mesh      libFuzzer (+ AddressSanitizer, UndefinedBehaviorSanitizer): the mesh readers, the vertex layout
#             (welding, splitting, carrying) and checks (raw bytes as OBJ, OFF, PLY, STL)
#   cage      libFuzzer: cage generation (bytes read as a recipe: a small shape, broken edits, extreme options)
#   scene, page, mount, settings, edits, gltf, gltf-resources, gltf-data, gltf-nodes, worker
#             fast-check in Node (scripts/fuzz_properties.mjs): the scene parser; the app's URL parameters and
#             embed attributes, mount() options, settings and handle edits; the glTF reader against random
#             edits of a valid file, hostile buffer uris, spoiled data: URIs and node forests (read, written
#             back, read again); the solver worker's messages
#   scripts/fuzz.sh [seconds] [target]      (default: $FUZZ_SECONDS or 60 s for each target)
# The libFuzzer targets build build/fuzz with clang (CMake option SD_FUZZ), seed build/fuzz/corpus-<target>, and
# a crashing input is left in build/fuzz/artifacts/ (keep it under tests/data/fuzz-regressions/ with a test that
# replays it, and fix the bug). Exits non-zero on a finding. Each target prints how many inputs it ran.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-${FUZZ_SECONDS:-60}}"
only="${2:-}"
out=build/fuzz
JS_TARGETS="scene page mount settings edits gltf gltf-resources gltf-data gltf-nodes worker"
wants() { [ -z "$only" ] || [ "$only" = "$1" ]; }

build_fuzz_targets() {
  local cxx
  cxx="$(command -v clang++-14 || command -v clang++ || true)"
  if [ -z "$cxx" ]; then
    echo "fuzz.sh: clang++ not found; install it with: apt-get install -y clang-14 libclang-rt-14-dev" >&2
    exit 2
  fi
  # -O2: Eigen at -O1 under the sanitizers runs ~70x slower than a release build, and slow units then hide
  # real hangs among false timeouts.
  cmake -S . -B "$out" -DSD_FUZZ=ON -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS="-O2 -g -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" >/dev/null
  echo "fuzz.sh: building the fuzz targets in $out"
  cmake --build "$out" -j "$(nproc 2>/dev/null || echo 2)" 2>&1 | { grep -vE '^\[ *[0-9]+%\]' || true; }
  mkdir -p "$out/artifacts"
}

seed_mesh_corpus() {
  local corpus="$out/corpus-mesh"
  mkdir -p "$corpus"
  # The hand-written test files, earlier crashes, and a few generated small meshes.
  find tests/data -type f ! -name '*.md' ! -name '*.json' -exec cp {} "$corpus/" \;
  printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$corpus/gen_tet.obj"
  printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4/1/1 -3//2 -2/3 -1\n' > "$corpus/gen_quad_neg.obj"
  printf 'OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$corpus/gen_tet.off"
  printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$corpus/gen_tri_ascii.ply"
  # Binary little-endian PLY with one triangle: float32 corners (1.0f = 00 00 80 3f), uchar count, int32 indices.
  { printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
    printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0'
    printf '\3\0\0\0\0\1\0\0\0\2\0\0\0'; } > "$corpus/gen_tri_le.ply"
  # Binary STL with one triangle: 80-byte header, count 1, normal, three corners, attribute.
  { printf 'binary stl%70s' ''; printf '\1\0\0\0'; printf '\0\0\0\0\0\0\0\0\0\0\200\77'
    printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0'; } > "$corpus/gen_tri_bin.stl"
  printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' > "$corpus/gen_tri_ascii.stl"
}

# Runs one libFuzzer target for $seconds from its corpus folder; an input slower than $3 seconds is a finding.
fuzz() {
  local target="$1" corpus="corpus-$2" timeout="$3"
  shift 3
  mkdir -p "$out/$corpus"
  echo "fuzz.sh: $target for $seconds s (crashing inputs go to $out/artifacts/)"
  (cd "$out" && "./$target" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout="$timeout" -print_final_stats=1 \
    -artifact_prefix=artifacts/ "$@" "$corpus")
}

if wants mesh || wants cage; then build_fuzz_targets; fi
if wants mesh; then
  seed_mesh_corpus
  fuzz fuzz_mesh mesh 30 -max_len=65536
fi
if wants cage; then
  # The recipe is a few dozen bytes (longer inputs only repeat its tail); start at full length, since at a
  # few executions per second libFuzzer would take hours to grow its length limit.
  # A cage takes up to a few seconds natively, ~10x that under the sanitizers.
  fuzz fuzz_cage cage 120 -max_len=64 -len_control=0
fi
for target in $JS_TARGETS; do
  if wants "$target"; then node scripts/fuzz_properties.mjs --seconds "$seconds" "$target"; fi
done
