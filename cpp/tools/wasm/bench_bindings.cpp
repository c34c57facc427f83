// Benchmark- and experiment-only bindings (used by scripts/bench.mjs and scripts/experiments.mjs, not by
// the app):
//   benchCase({ n, segments, repeats?, bindRepeats?, solveRepeats?, frames?, exactMaxN?, fullMaxN?, arap?, float32? })
//     runs cpp/tools/bench_case.h inside wasm (the same code as the native tool bench_native_cases) and
//     returns its named numbers as an object;
//   benchEvaluateEnergy(restPositions, indices, X, handleVertices, targets, positionWeight)
//     -> { energy, laplacianEnergy, positionEnergy, volume }: the energy of docs/method.md section 5 at any X,
//     so results of every method (ARAP included) are measured by one yardstick;
//   benchArapEnergy(restPositions, indices, X) -> the ARAP energy (best rotations) at X;
//   benchReadBandwidth(megabytes) -> single-thread streaming read GB/s inside wasm;
//   benchIntegration({ n, segments?, frames?, float32?, solve? }): cpp/tools/bench_integration.h, full against reduced
//     integration at one mesh size.
#include <emscripten/bind.h>

#include <climits>
#include <string>
#include <vector>

#include "bindings/convert.h"
#include "core/arap/arap.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "tools/bench_case.h"
#include "tools/bench_integration.h"

namespace sd::bindings {
namespace {

int int_option(const val& o, const char* key, int fallback) {
  const val v = o[key];
  if (!present(v)) return fallback;
  return integer_in(v, std::string("benchCase: ") + key, 0, INT_MAX);
}

val bench_case(const val& o) {
  return guarded([&] {
    bench::CaseOptions c;
    c.n_target = int_option(o, "n", c.n_target);
    c.cage_segments = int_option(o, "segments", c.cage_segments);
    c.repeats = int_option(o, "repeats", c.repeats);
    c.bind_repeats = int_option(o, "bindRepeats", c.bind_repeats);
    c.solve_repeats = int_option(o, "solveRepeats", c.solve_repeats);
    c.frames = int_option(o, "frames", c.frames);
    c.exact_max_n = int_option(o, "exactMaxN", c.exact_max_n);
    c.full_max_n = int_option(o, "fullMaxN", c.full_max_n);
    if (!o["arap"].isUndefined()) c.arap = o["arap"].as<bool>();
    if (!o["float32"].isUndefined()) c.float32 = o["float32"].as<bool>();
    val out = val::object();
    for (const auto& [key, value] : bench::run_case(c)) out.set(key, value);
    return out;
  });
}

// benchIntegration({ n, segments?, frames?, float32?, solve? }): cpp/tools/bench_integration.h.
val bench_integration(const val& o) {
  return guarded([&] {
    bench::IntegrationOptions c;
    c.n_target = int_option(o, "n", c.n_target);
    c.cage_segments = int_option(o, "segments", c.cage_segments);
    c.frames = int_option(o, "frames", c.frames);
    if (!o["float32"].isUndefined()) c.float32 = o["float32"].as<bool>();
    if (!o["solve"].isUndefined()) c.solve = o["solve"].as<bool>();
    val out = val::object();
    for (const auto& [key, value] : bench::run_integration_case(c)) out.set(key, value);
    return out;
  });
}

std::vector<int> indices_from_js(const val& array) {
  const unsigned length = array["length"].as<unsigned>();
  std::vector<int> out(length);
  for (unsigned k = 0; k < length; ++k) out[k] = static_cast<int>(array[k].as<double>());
  return out;
}

val evaluate_energy(const val& rest, const val& indices, const val& X, const val& handles, const val& targets,
                    double weight) {
  return guarded([&] {
    const Mesh mesh = mesh_from_js(rest, indices, "mesh");
    const Vertices x = vertices_from_js(X, "X");
    if (x.rows() != mesh.V.rows()) throw Error("benchEvaluateEnergy: X and the rest mesh differ in vertex count");
    DeformationEnergy energy(mesh.V, mesh.F);
    const std::vector<int> h = indices_from_js(handles);
    for (int v : h)
      if (v < 0 || v >= mesh.V.rows())
        throw Error("benchEvaluateEnergy: handle vertex " + std::to_string(v) + " out of range");
    energy.set_handles(h);
    energy.set_targets(vertices_from_js(targets, "targets"));
    energy.set_position_weight(weight);
    const EnergyEvaluation e = energy.evaluate(x);
    val out = val::object();
    out.set("energy", e.energy);
    out.set("laplacianEnergy", e.laplacian_energy);
    out.set("positionEnergy", e.position_energy);
    out.set("volume", e.volume);
    out.set("restVolume", energy.rest_volume());
    return out;
  });
}

double arap_energy(const val& rest, const val& indices, const val& X) {
  return guarded([&] {
    const Mesh mesh = mesh_from_js(rest, indices, "mesh");
    ArapSolver solver(mesh.V, mesh.F);
    return solver.energy(vertices_from_js(X, "X"));
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(bench) {
  using namespace sd::bindings;
  emscripten::function("benchCase", &bench_case);
  emscripten::function("benchIntegration", &bench_integration);
  emscripten::function("benchReadBandwidth", &sd::bench::read_bandwidth_gbs);
  emscripten::function("benchEvaluateEnergy", &evaluate_energy);
  emscripten::function("benchArapEnergy", &arap_energy);
}
