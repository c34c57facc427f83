// Experiment- and benchmark-only bindings for the spectral subspace and the step's conditioning (used by
// scripts/experiments.mjs; not in the module pages load):
//   benchStepConditioning(restPositions, indices, X, handleVertices, targets, positionWeight, basis)
//     basis: { kind: 'full' } | { kind: 'cage', positions, indices, coordinates?, pmvcResolution?, harmonicResolution?
//     }
//            | { kind: 'spectral', modes }
//     -> { smallest, largest, condition } of the Gauss-Newton normal matrix at X (step_conditioning.h), and for a
//        subspace also `orthonormal`: the same in an orthonormal basis of the subspace;
//   benchSpectralBasis(n, modes) -> { ms, eigenMs, orthonormalizeMs, solves, columns, memoryMB }: the cost of
//     the spectral basis on the benchmark capsule of about n vertices (bench_case.h), inside wasm.
#include <emscripten/bind.h>

#include <climits>
#include <string>
#include <vector>

#include "bindings/convert.h"
#include "core/timer.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/steps/step_conditioning.h"
#include "core/basis/spectral_basis.h"
#include "tools/bench_case.h"

namespace sd::bindings {
namespace {

val conditioning_to_js(const StepConditioning& c) {
  val out = val::object();
  out.set("smallest", c.smallest);
  out.set("largest", c.largest);
  out.set("condition", c.condition);
  return out;
}

val step_conditioning(const val& rest, const val& indices, const val& X, const val& handles, const val& targets,
                      double weight, const val& basis) {
  return guarded([&] {
    const Mesh mesh = mesh_from_js(rest, indices, "mesh");
    const Vertices x = vertices_from_js(X, "X");
    if (x.rows() != mesh.V.rows()) throw Error("benchStepConditioning: X and the rest mesh differ in vertex count");
    DeformationEnergy energy(mesh.V, mesh.F);
    energy.set_handles(
        ints_from_js(handles, "benchStepConditioning: handle vertex", 0, static_cast<int>(mesh.V.rows()) - 1));
    energy.set_targets(vertices_from_js(targets, "targets"));
    energy.set_position_weight(weight);
    const std::string kind = basis["kind"].as<std::string>();
    if (kind == "full") return conditioning_to_js(full_space_conditioning(energy, x));
    BasisMatrix W;
    if (kind == "cage") {
      W = cage_coordinates(mesh.V, mesh_from_js(basis["positions"], basis["indices"], "cage"), {},
                           coordinates_from_js(basis));
    } else if (kind == "spectral") {
      SpectralOptions options;
      options.modes = integer_in(basis["modes"], "modes", 1, INT_MAX);
      W = spectral_basis(mesh, options).B;
    } else {
      throw Error("benchStepConditioning: basis.kind must be 'full', 'cage' or 'spectral'");
    }
    val out = conditioning_to_js(subspace_conditioning(energy, W, x, false));
    out.set("orthonormal", conditioning_to_js(subspace_conditioning(energy, W, x, true)));
    return out;
  });
}

val spectral_basis_cost(int n, int modes) {
  return guarded([&] {
    const Mesh mesh = bench::capsule(n);
    SpectralOptions options;
    options.modes = modes;
    options.memory_budget_bytes = std::size_t(3) << 30;
    const Timer timer;
    const SpectralBasis basis = spectral_basis(mesh, options);
    const double ms = timer.ms();
    val out = val::object();
    out.set("n", static_cast<int>(mesh.V.rows()));
    out.set("modes", modes);
    out.set("ms", ms);
    out.set("eigenMs", basis.eigen_ms);
    out.set("orthonormalizeMs", basis.orthonormalize_ms);
    out.set("solves", basis.operations);
    out.set("columns", basis.B.cols());
    out.set("memoryMB", spectral_basis_memory_bytes(static_cast<int>(mesh.V.rows()), modes) / 1e6);
    return out;
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(spectral_bench) {
  using namespace sd::bindings;
  emscripten::function("benchStepConditioning", &step_conditioning);
  emscripten::function("benchSpectralBasis", &spectral_basis_cost);
}
