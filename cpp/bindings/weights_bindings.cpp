// Cage coordinates W for JS (mean value, positive mean value or harmonic): one call computes the whole n x m
// matrix and copies it out.
// Wrapped by web/lib/weights.js, which validates arguments before they get here.
#include <emscripten/bind.h>

#include "bindings/convert.h"
#include "core/timer.h"
#include "core/basis/cage_coordinates.h"

namespace sd::bindings {
namespace {

// computeWeights(points: Float64Array (xyz), cagePositions: Float64Array, cageIndices: Uint32Array,
//                options: { float32?: boolean, memoryBudgetMB?: number, coordinates?: 'mvc' | 'pmvc' | 'harmonic',
//                           pmvcResolution?, harmonicResolution? }, progress?: (fraction) => boolean|void)
// -> { weights: Float64Array | Float32Array (rows x cols, row-major), rows, cols, bytes, evaluations, ms, and
//      coordinates_report_to_js's fields (convert.h) }
// progress is called every few hundred rows; returning false cancels (Error "binding cancelled").
val compute_weights_js(const val& points, const val& cage_positions, const val& cage_indices, const val& options,
                       const val& progress) {
  return guarded([&] {
    const Timer timer;
    const Vertices X = vertices_from_js(points, "points");
    const Mesh cage = mesh_from_js(cage_positions, cage_indices, "cage");
    const MvcOptions mvc = mvc_options_from_js(options, progress);
    CoordinatesReport report;
    const BasisMatrix W = cage_coordinates(X, cage, mvc, coordinates_from_js(options), &report);
    const size_t count = static_cast<size_t>(W.rows()) * static_cast<size_t>(W.cols());
    val out = coordinates_report_to_js(report);
    if (W.single_precision())
      out.set("weights",
              val(emscripten::typed_memory_view(count, static_cast<const float*>(W.data()))).call<val>("slice"));
    else out.set("weights", float64_array(static_cast<const double*>(W.data()), count));
    out.set("rows", W.rows());
    out.set("cols", W.cols());
    out.set("bytes", static_cast<double>(W.bytes()));
    out.set("evaluations", report.binding.evaluations);
    out.set("ms", timer.ms());
    return out;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(weights) { emscripten::function("computeWeights", &compute_weights_js); }

}  // namespace sd::bindings
