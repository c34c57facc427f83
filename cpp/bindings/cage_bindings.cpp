// Automatic cage generation for JS (issue 8). Wrapped by web/lib/cage.js, which validates
// arguments before they get here.
#include <emscripten/bind.h>

#include <cmath>

#include "bindings/convert.h"
#include "core/cage/cage_generation.h"
#include "core/timer.h"

namespace sd::bindings {
namespace {

// generateCage(positions: Float64Array, indices: Uint32Array, options: { vertices: number, offset?: number,
//              resolution?: number }, progress?: (fraction) => boolean|void)
// -> { positions: Float64Array, indices: Uint32Array, offset, voxelSize, attempts, startVertices,
//      volumeRatio, startVolumeRatio, minClearance, ms }
// progress is called now and then with the fraction done; returning false cancels ("cage generation cancelled").
val generate_cage_js(const val& positions, const val& indices, const val& options, const val& progress) {
  return guarded([&] {
    const Timer timer;
    const Mesh mesh = mesh_from_js(positions, indices, "mesh");
    CageOptions cage_options;
    auto number = [&](const char* key, double fallback) {
      const val v = options[key];
      if (!present(v)) return fallback;
      const double x = is_number(v) ? v.as<double>() : std::nan("");
      if (!std::isfinite(x)) throw Error(std::string("generateCage: options.") + key + " must be a finite number");
      return x;
    };
    if (present(options["vertices"]))
      cage_options.target_vertices = integer_in(options["vertices"], "generateCage: options.vertices", 4, INT_MAX);
    cage_options.offset = number("offset", 0.0);
    if (present(options["resolution"]))  // 0: automatic
      cage_options.resolution = integer_in(options["resolution"], "generateCage: options.resolution", 0, INT_MAX);
    cage_options.progress = progress_from_js(progress);
    const CageResult result = generate_cage(mesh, cage_options);
    val out = mesh_to_js(result.cage);
    out.set("offset", result.offset);
    out.set("voxelSize", result.voxel_size);
    out.set("attempts", result.attempts);
    out.set("startVertices", result.start_vertices);
    out.set("volumeRatio", result.volume_ratio);
    out.set("startVolumeRatio", result.start_volume_ratio);
    out.set("minClearance", result.min_clearance);
    out.set("ms", timer.ms());
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(cage) {
  emscripten::function("generateCage", &generate_cage_js);
}

}  // namespace sd::bindings
