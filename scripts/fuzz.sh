#!/usr/bin/env bash
# Fuzzes the mesh readers and checks with libFuzzer for a bounded time.
#   scripts/fuzz.sh [seconds] [extra libFuzzer flags...]     (default: $FUZZ_SECONDS or 60 s)
# Builds build/fuzz/fuzz_mesh with clang (-fsanitize=fuzzer,address,undefined), seeds build/fuzz/corpus
# from tests/data plus small generated files, and exits non-zero on a crash; the crashing input is
# left in build/fuzz/artifacts/ (keep it as tests/data/fuzz-regressions/<name> and fix the bug).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds="${1:-${FUZZ_SECONDS:-60}}"
shift || true
out=build/fuzz
cxx="$(command -v clang++-14 || command -v clang++ || true)"
if [ -z "$cxx" ]; then
  echo "fuzz.sh: clang++ not found; install it with: apt-get install -y clang-14 libclang-rt-14-dev" >&2
  exit 2
fi
mkdir -p "$out/corpus" "$out/artifacts"

sources=(tests/fuzz/fuzz_mesh.cpp cpp/core/error.cpp cpp/core/mesh/mesh_io.cpp cpp/core/mesh/internal/*.cpp
         cpp/core/mesh/mesh_check.cpp cpp/core/mesh/mesh.cpp cpp/core/geometry/point_triangle_distance.cpp
         cpp/core/geometry/winding_number.cpp)
stale=0
[ -x "$out/fuzz_mesh" ] || stale=1
for s in "${sources[@]}" cpp/core/*.h; do [ "$s" -nt "$out/fuzz_mesh" ] && stale=1; done
if [ "$stale" = 1 ]; then
  echo "fuzz.sh: building $out/fuzz_mesh"
  "$cxx" -std=c++17 -g -O1 -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=all \
    -Icpp -I/usr/include/eigen3 "${sources[@]}" -o "$out/fuzz_mesh"
fi

# Seeds: the hand-written test files, earlier crashes, and a few generated small meshes.
find tests/data -type f ! -name '*.md' -exec cp {} "$out/corpus/" \;
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' > "$out/corpus/gen_tet.obj"
printf 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4/1/1 -3//2 -2/3 -1\n' > "$out/corpus/gen_quad_neg.obj"
printf 'OFF\n4 4 6\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n' > "$out/corpus/gen_tet.off"
printf 'ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$out/corpus/gen_tri_ascii.ply"
# Binary little-endian PLY with one triangle: float32 corners (1.0f = 00 00 80 3f), uchar count, int32 indices.
{ printf 'ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n'
  printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0'
  printf '\3\0\0\0\0\1\0\0\0\2\0\0\0'; } > "$out/corpus/gen_tri_le.ply"
# Binary STL with one triangle: 80-byte header, count 1, normal, three corners, attribute.
{ printf 'binary stl%70s' ''; printf '\1\0\0\0'; printf '\0\0\0\0\0\0\0\0\0\0\200\77'
  printf '\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0\0\0\0\0\0\0\0\0\200\77\0\0\0\0\0\0'; } > "$out/corpus/gen_tri_bin.stl"
printf 'solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' > "$out/corpus/gen_tri_ascii.stl"

echo "fuzz.sh: fuzzing for $seconds s (crashing inputs go to $out/artifacts/)"
cd "$out"  # with -jobs=N libFuzzer writes fuzz-N.log into the current directory
./fuzz_mesh -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 -print_final_stats=1 \
  -artifact_prefix=artifacts/ "$@" corpus
