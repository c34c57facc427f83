// Native benchmark of automatic cage generation (docs/cage.md). Usage:
//   bench_cage [mesh file | -] [K=200] [offset | 0] [voxels along the longest side | 0]
// Without a file it uses a procedural 25k-vertex capsule. Prints sizes, checks, volume ratio and times.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "core/cage/cage_generation.h"
#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/shapes.h"
#include "core/timer.h"
#include "tools/read_mesh_file.h"

int main(int argc, char** argv) {
  try {
    sd::Mesh mesh;
    std::string name = "capsule";
    if (argc > 1 && std::string(argv[1]) != "-") {
      mesh = sd::tools::read_mesh_file(argv[1]);
      name = argv[1];
    } else {
      mesh = sd::make_capsule(3.0, 0.6, 30, 60, 208);
    }
    sd::CageOptions options;
    options.target_vertices = argc > 2 ? std::atoi(argv[2]) : 200;
    if (argc > 3) options.offset = std::atof(argv[3]);
    if (argc > 4) options.resolution = std::atoi(argv[4]);
    const sd::Timer timer;
    sd::CageResult result = sd::generate_cage(mesh, options);
    const double ms = timer.ms();
    std::printf("%s: %d vertices -> cage %d vertices, %d faces (voxel surface %d vertices, attempts %d)\n",
                name.c_str(), int(mesh.V.rows()), int(result.cage.V.rows()), int(result.cage.F.rows()),
                result.start_vertices, result.attempts);
    std::printf(
        "offset %.4g (%.2f%% of diagonal), min clearance %.4g, volume ratio %.3f (voxel surface %.3f), %.0f ms\n",
        result.offset, 100 * result.offset / sd::bounding_box_diagonal(mesh.V), result.min_clearance,
        result.volume_ratio, result.start_volume_ratio, ms);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_cage: %s\n", e.what());
    return 1;
  }
}
