// The integration benchmark of scripts/bench.mjs (--integration; docs/benchmarks.md): what an iteration costs as
// the mesh grows with the subspace fixed, with the Laplacian term summed over every vertex and with reduced
// integration, on the bend scene of bench_case.h (capsule of about n vertices in a bar cage of m = 4 (segments
// + 1) vertices). Shared by the native tool bench_integration and the wasm binding benchIntegration, so both
// time the same code.
//
// Measured: the binding (W, B, the reduced rule) and W's bytes; a drag of `frames` frames (the moving end
// pulled a little further each frame, one warm-started iteration per frame, the median ms per iteration) with
// each integration; a converged solve with each, the reduced solve's shape against the full one (largest vertex
// distance over the diagonal), both volume errors, and the reduced solve's energy summed over every vertex.
#pragma once

#include "tools/bench_case.h"

namespace sd::bench {

struct IntegrationOptions {
  int n_target = 50000;
  int cage_segments = 24;  // m = 100
  int frames = 9;
  bool float32 = false;
  bool solve = true;  // also the converged solves (the shape difference)
};

inline double drag_iteration_ms(Deformer& d, const Scene& s, int frames, int* samples = nullptr) {
  Vertices dragged = s.targets;
  std::vector<double> times;
  const Eigen::Index first_moving = static_cast<Eigen::Index>(s.groups[0].size());
  for (int f = 0; f < std::max(1, frames); ++f) {
    for (Eigen::Index k = first_moving; k < dragged.rows(); ++k) dragged(k, 1) -= 0.01;
    d.set_targets(dragged);
    const StepResult r = d.step(1);
    if (!r.iterations.empty()) {
      times.push_back(r.iterations.back().ms);
      if (samples) *samples = r.iterations.back().samples;
    }
  }
  d.set_targets(s.targets);
  return median(times);
}

inline Results run_integration_case(const IntegrationOptions& o) {
  Results out;
  auto put = [&out](const std::string& k, double v) { out.emplace_back(k, v); };
  const Scene s = bend_scene(o.n_target, o.cage_segments);
  const double diagonal = bounding_box_diagonal(s.mesh.V);
  put("n", static_cast<double>(s.mesh.V.rows()));
  put("m", static_cast<double>(s.cage.V.rows()));
  put("float32", o.float32 ? 1 : 0);
  MvcOptions bind;
  bind.single_precision = o.float32;
  bind.memory_budget_bytes = std::size_t(3) << 30;
  Deformer d(s.mesh, s.cage, bind);
  put("bindMs", d.bind_ms());
  put("precomputeMs", d.precompute_ms());
  put("wBytes", static_cast<double>(d.basis().bytes()));
  d.set_handles(s.groups);
  d.set_targets(s.targets);
  double t0 = now_ms();
  d.prepare_reduced();
  put("fitMs", now_ms() - t0);
  const ReducedIntegrationInfo info = d.reduced_integration();
  put("samples", info.samples);
  put("testError", info.test_error);

  SolverOptions full, reduced;
  reduced.integration = Integration::Reduced;
  int samples = 0;
  d.set_options(full);
  put("fullIterationMs", drag_iteration_ms(d, s, o.frames));
  d.set_options(reduced);
  put("reducedIterationMs", drag_iteration_ms(d, s, o.frames, &samples));
  put("dragSamples", samples);
  if (!o.solve) return out;

  d.set_options(full);
  d.reset();
  t0 = now_ms();
  const StepResult a = d.solve();
  put("fullSolveMs", now_ms() - t0);
  put("fullSolveIterations", static_cast<double>(a.iterations.size()));
  put("fullVolumeRelError", a.iterations.empty() ? NAN : a.iterations.back().volume_rel_error);
  put("fullEnergy", d.full_energy());
  const Vertices X = d.positions();
  d.set_options(reduced);
  d.reset();
  t0 = now_ms();
  const StepResult b = d.solve();
  put("reducedSolveMs", now_ms() - t0);
  put("reducedSolveIterations", static_cast<double>(b.iterations.size()));
  put("reducedConverged", b.converged ? 1 : 0);
  put("reducedVolumeRelError", b.iterations.empty() ? NAN : b.iterations.back().volume_rel_error);
  put("reducedFullEnergy", d.full_energy());
  put("shapeDifference", (d.positions() - X).rowwise().norm().maxCoeff() / diagonal);
  return out;
}

}  // namespace sd::bench
