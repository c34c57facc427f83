// Native benchmark of the Gauss-Newton solver (cost model and speed goals in docs/benchmarks.md).
// A capsule bar of ~5k / 20k / 50k vertices in a bar cage of m vertices; the right end is bent down.
// Prints, per size: the streaming floor (one W pass), one matrix-free product W^T J^T J W v (two passes
// + the sparse Jacobian work), the Jacobian assembly, one warm-started fast step, a converged fast solve
// (iterations and products), and for small n the exact subspace and full-space iteration costs.
//
//   build/<dir>/bench_solver [sizes...]       e.g. bench_solver 5000 20000 50000   (default: 5000 20000)
//   env SD_BENCH_CAGE_SEGMENTS=74 (m = 4 (segments + 1) = 300 cage vertices; default 24 -> m = 100)
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/deformer.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "bench_case.h"

using namespace sd;

namespace {

// The scene, the clock and the medians are bench_case.h's, so this tool and scripts/bench.mjs time the same.
using bench::median_ms;
using sd::now_ms;

void run(int n_target, int cage_segments, bool exact) {
  const bench::Scene s = bench::bend_scene(n_target, cage_segments);  // the scene bench.mjs times too
  const int n = static_cast<int>(s.mesh.V.rows());
  double t0 = now_ms();
  Deformer d(s.mesh, s.cage);
  const double create_ms = now_ms() - t0;
  const BasisMatrix& W = d.basis();
  const int m = W.cols();
  std::printf("n = %d, m = %d (W %.0f MB): bind %.0f ms, precompute B %.0f ms, session total %.0f ms\n", n, m,
              W.bytes() / 1e6, d.bind_ms(), d.precompute_ms(), create_ms);

  t0 = now_ms();
  d.set_handles(s.groups);
  const double handles_ms = now_ms() - t0;
  d.set_targets(s.targets);

  // Pieces at the rest pose with the bend targets.
  DeformationEnergy energy(s.mesh.V, s.mesh.F);
  bench::set_scene_handles(energy, s);
  SubspaceStep sub(energy, W);
  sub.refactor(energy);
  const Eigen::MatrixXd V3 = Eigen::MatrixXd::Random(m, 3), V6 = Eigen::MatrixXd::Random(m, 6);
  Eigen::MatrixXd out, image;
  const int reps = n > 30000 ? 5 : 9;
  const double pass3 = median_ms([&] { W.multiply(V3, out); }, reps);
  const double pass6 = median_ms([&] { W.multiply(V6, out); }, reps);
  const Eigen::MatrixXd R6 = Eigen::MatrixXd::Random(n, 6);
  const double tpass6 = median_ms([&] { W.multiply_transpose(R6, out); }, reps);
  const double eval_ms = median_ms([&] { energy.evaluate(s.mesh.V); }, reps);
  const double jac_ms = median_ms([&] { energy.jacobian(s.mesh.V); }, reps);
  const EnergyJacobian J = energy.jacobian(s.mesh.V);
  const double jtj_ms = median_ms([&] { J.normal_product(R6); }, reps);
  const double product_ms = median_ms([&] { sub.product(J, V6, image); }, reps);
  std::printf("  W pass (x,y,z) %.2f ms, W pass (6 columns) %.2f ms, W^T pass (6 columns) %.2f ms\n", pass3, pass6,
              tpass6);
  std::printf(
      "  product W^T J^T J W [6 columns]: %.2f ms = %.2fx the streaming floor (two 6-column passes %.2f ms);"
      " of which J^T J %.2f ms\n",
      product_ms, product_ms / (pass6 + tpass6), pass6 + tpass6, jtj_ms);
  std::printf("  energy evaluation %.2f ms, Jacobian assembly %.2f ms, set_handles (factor N) %.2f ms\n", eval_ms,
              jac_ms, handles_ms);

  // Converged fast solve from rest.
  SolverOptions o;
  d.set_options(o);
  d.reset();
  t0 = now_ms();
  const StepResult r = d.solve();
  const double solve_ms = now_ms() - t0;
  const int products = bench::total_products(r), passes = bench::total_passes(r);
  std::printf("  fast solve: %zu iterations, %d products, %d W passes, %.0f ms, energy %.6g, volume error %.1e (%s)\n",
              r.iterations.size(), products, passes, solve_ms, r.iterations.back().energy,
              r.iterations.back().volume_rel_error, r.stop_reason.c_str());
  for (const auto& it : r.iterations)
    std::printf("    it %d: energy %.8g step %.2e cg %d trials %d ms %.1f\n", it.iteration, it.energy, it.step,
                it.inner_iterations, it.line_search_trials, it.ms);

  // One interactive frame: the handles moved a little from the converged state, one warm-started step.
  Vertices dragged = s.targets;
  for (Eigen::Index k = static_cast<Eigen::Index>(s.groups[0].size()); k < dragged.rows(); ++k) dragged(k, 1) -= 0.01;
  d.set_targets(dragged);
  const StepResult frame = d.step(1);
  std::printf("  interactive frame (one warm-started fast step after a small drag): %.1f ms, %d products\n",
              frame.iterations.empty() ? 0.0 : frame.iterations[0].ms,
              frame.iterations.empty() ? 0 : frame.iterations[0].products);

  if (exact) {
    o.jacobian = JacobianMode::Exact;
    d.set_options(o);
    d.reset();
    const StepResult e = d.step(2);
    std::printf("  exact subspace: %.0f ms per iteration\n", e.iterations.back().ms);
    o.method = Method::Full;
    d.set_options(o);
    const StepResult fe = d.step(2);
    std::printf("  full space exact: %.0f ms per iteration\n", fe.iterations.back().ms);
    o.jacobian = JacobianMode::Fast;
    d.set_options(o);
    const StepResult ff = d.solve();
    double ms = 0;
    int cg = 0;
    for (const auto& it : ff.iterations) {
      ms += it.ms;
      cg += it.inner_iterations;
    }
    std::printf("  full space fast: %zu iterations, %.0f ms per iteration, %.0f CG iterations per step (%s)\n",
                ff.iterations.size(), ms / ff.iterations.size(), double(cg) / ff.iterations.size(),
                ff.stop_reason.c_str());
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  if (sizes.empty()) sizes = {5000, 20000};
  const char* seg = std::getenv("SD_BENCH_CAGE_SEGMENTS");
  const int segments = seg ? std::atoi(seg) : 24;
  for (int n : sizes) run(n, segments, n <= 6000);
  return 0;
}
