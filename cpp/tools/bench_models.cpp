// Native benchmark of the Gauss-Newton solver on a real model in its own cage (docs/benchmarks.md, "Real
// models"): the model is fixed at one end of its longest axis, and the other end is pulled sideways (along the
// second-longest axis) by 8% of the diagonal and turned 20 degrees about the third axis. The same scene as
// scripts/bench/models.mjs times in wasm (tools/drag_scene.h defines it).
//
//   bench_models mesh.obj cage.obj [--integration full|reduced|both] [--threads T] [--frames F]
//                [--preconditioner gauss-newton|constant] [--cg-tolerance TOL] [--float32 0|1] [--app F]
//
// Prints one JSON object per integration: the converged solve from rest (iterations, of which finishing ones on every
// vertex after a reduced rule's, docs/method.md section 17.3; the reduced rule's making, timed apart; wall ms, ms per
// iteration, products and W passes per iteration, stop code, energy summed over every vertex; the factor
// preconditioner's pose-free parts, made before it like the rule and timed apart as factorPartsMs) and the
// interactive drag: F frames that move the target a little further, one step() each, with their median ms, and the
// release: the solve to convergence at the drag's last targets with full integration (the app's settle; after a
// reduced drag it starts with the switch to full integration).
// --float32 1 stores W in single precision (as the app's worker does above FLOAT32_ABOVE_BYTES).
// With both integrations, also the largest distance between the two converged shapes over the diagonal.
// shapeHash and dragHash (FNV-1a over the positions' bytes after the solve and after the drag) tell runs with other
// thread counts apart: the threads' rules promise the same bits (scripts/bench/model_threads.mjs compares them).
// --app F runs the app's sequence instead (docs/app.md, "drag integration" auto on a large model): the rule and the
// factor's parts made as at load, F frames of reduced integration from rest that carry the pull from 0 to its full
// length (one step() each), then the settle with full integration; one JSON object with the frames' and the settle's
// times and the settle's products per iteration.
// SD_BENCH_TRACE=1 also prints each iteration of the solve and the settle (merit, alpha, products, step, ms) to stderr.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/parallel/thread_pool.h"
#include "core/solver/deformer.h"
#include "tools/bench_case.h"
#include "tools/drag_scene.h"
#include "tools/read_mesh_file.h"

using namespace sd;

namespace {

// FNV-1a (64 bits) over the bytes of the positions: equal shapes give equal hashes, and one changed bit another.
std::uint64_t shape_hash(const Vertices& V) {
  std::uint64_t h = 14695981039346656037ull;
  const auto* bytes = reinterpret_cast<const unsigned char*>(V.data());
  for (size_t i = 0; i < sizeof(double) * static_cast<size_t>(V.size()); ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}

// With SD_BENCH_TRACE set, each iteration of a solve on stderr.
void trace(const char* what, const StepResult& r) {
  if (!std::getenv("SD_BENCH_TRACE")) return;
  for (const auto& it : r.iterations)
    std::fprintf(stderr, "  %s it %d: merit %.9g alpha %.3g products %d passes %d step %.3g ms %.1f\n", what,
                 it.iteration, it.merit, it.alpha, it.products, it.passes, it.step, it.ms);
}

// The frames of a drag: the pull carried from `from` to `to` of its length in `frames` frames, one step() each (as
// the app's worker does), with each frame's time and products.
struct Frames {
  std::vector<double> ms, products;
};
Frames drag_frames(Deformer& d, const tools::DragScene& scene, double from, double to, int frames) {
  Frames out;
  for (int f = 1; f <= frames; ++f) {
    d.set_targets(scene.targets(from + (to - from) * f / frames));
    const double t0 = now_ms();
    const StepResult s = d.step(1);
    out.ms.push_back(now_ms() - t0);
    out.products.push_back(s.iterations.empty() ? 0 : s.iterations.back().products);
  }
  return out;
}

// The converged shape of the solve (before the drag's frames move it on).
Vertices run(Deformer& d, const tools::DragScene& scene, Integration integration, int frames) {
  SolverOptions o = d.options();
  o.integration = integration;
  d.set_options(o);
  d.reset();
  d.set_targets(scene.targets(1.0));
  double t0 = now_ms();
  if (integration == Integration::Reduced) d.prepare_reduced();  // made once per model (the app: at load)
  const double rule_ms = now_ms() - t0;
  t0 = now_ms();
  d.prepare_factor();  // the factor's pose-free parts, made once per model (the app: at load, after the rule)
  const double factor_parts_ms = now_ms() - t0;
  t0 = now_ms();
  const StepResult r = d.solve();
  const double solve_ms = now_ms() - t0;
  const int its = static_cast<int>(r.iterations.size());
  const auto finishing =
      std::count_if(r.iterations.begin(), r.iterations.end(), [](const auto& it) { return it.finishing; });
  std::vector<double> it_ms, products, passes;
  for (const auto& it : r.iterations) {
    it_ms.push_back(it.ms);
    products.push_back(it.products);
    passes.push_back(it.passes);
  }
  Vertices out = d.positions();
  const double full_energy = d.full_energy();  // of the converged shape, before the drag moves it on
  trace("solve", r);
  // The drag: frames that carry the pull a little further, one iteration each (as the app's worker does).
  const Frames drag = drag_frames(d, scene, 1.0, 1.25, frames);
  const ReducedIntegrationInfo info = d.reduced_integration();
  const Vertices dragged = d.positions();
  // The release: solved to convergence at the drag's last targets with full integration, as the app settles.
  o.integration = Integration::Full;
  d.set_options(o);
  t0 = now_ms();
  const StepResult settle = d.solve();
  const double settle_ms = now_ms() - t0;
  trace("settle", settle);
  std::printf(
      "{\"integration\": \"%s\", \"n\": %d, \"m\": %d, \"iterations\": %d, \"converged\": %s, \"stop\": \"%s\", "
      "\"finishingIterations\": %d, \"ruleMs\": %.1f, \"factorPartsMs\": %.1f, \"solveMs\": %.1f, \"msPerIteration\": "
      "%.2f, "
      "\"productsPerIteration\": %.2f, \"maxProducts\": %.0f, "
      "\"passesPerIteration\": %.2f, \"fullEnergy\": %.6g, \"samples\": %d, \"testError\": %.3g, "
      "\"frameMs\": %.2f, \"frameProducts\": %.1f, \"settleMs\": %.1f, \"settleIterations\": %d, \"settleStop\": "
      "\"%s\", "
      "\"shapeHash\": \"%016llx\", \"dragHash\": \"%016llx\"}\n",
      integration == Integration::Reduced ? "reduced" : "full", static_cast<int>(d.rest_mesh().V.rows()),
      d.basis().cols(), its, r.converged ? "true" : "false", stop_code_name(r.stop), static_cast<int>(finishing),
      rule_ms, factor_parts_ms, solve_ms, bench::median(it_ms), bench::median(products),
      *std::max_element(products.begin(), products.end()), bench::median(passes), full_energy, info.samples,
      info.test_error, bench::median(drag.ms), bench::median(drag.products), settle_ms,
      static_cast<int>(settle.iterations.size()), stop_code_name(settle.stop),
      static_cast<unsigned long long>(shape_hash(out)), static_cast<unsigned long long>(shape_hash(dragged)));
  std::fflush(stdout);
  return out;
}

// The app's drag of a large model and its settle (--app F).
void app_drag(Deformer& d, const tools::DragScene& scene, int frames) {
  SolverOptions o = d.options();
  o.integration = Integration::Reduced;
  d.set_options(o);
  d.reset();
  d.prepare_reduced();
  d.prepare_factor();
  const Frames drag = drag_frames(d, scene, 0.0, 1.0, frames);
  o.integration = Integration::Full;
  d.set_options(o);
  const double t0 = now_ms();
  const StepResult settle = d.solve();
  const double settle_ms = now_ms() - t0;
  trace("settle", settle);
  std::string products;
  for (const auto& it : settle.iterations) products += (products.empty() ? "" : ", ") + std::to_string(it.products);
  std::printf(
      "{\"app\": true, \"frames\": %d, \"frameMs\": %.2f, \"frameProducts\": %.1f, \"settleMs\": %.1f, "
      "\"settleIterations\": %d, \"settleStop\": \"%s\", \"settleProducts\": [%s], \"shapeHash\": \"%016llx\"}\n",
      frames, bench::median(drag.ms), bench::median(drag.products), settle_ms,
      static_cast<int>(settle.iterations.size()), stop_code_name(settle.stop), products.c_str(),
      static_cast<unsigned long long>(shape_hash(d.positions())));
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(
        stderr,
        "usage: bench_models mesh.obj cage.obj [--integration full|reduced|both] [--threads T] "
        "[--frames F] [--preconditioner gauss-newton|constant] [--cg-tolerance TOL] [--float32 0|1] [--app F]\n");
    return 2;
  }
  std::string integration = "both";
  int frames = 10, app_frames = 0;
  SolverOptions options;
  MvcOptions bind;
  for (int a = 3; a + 1 < argc; a += 2) {
    const std::string flag = argv[a];
    if (flag == "--integration") integration = argv[a + 1];
    else if (flag == "--threads") parallel::set_threads(std::atoi(argv[a + 1]));
    else if (flag == "--frames") frames = std::atoi(argv[a + 1]);
    else if (flag == "--app") app_frames = std::atoi(argv[a + 1]);
    else if (flag == "--float32") bind.single_precision = std::atoi(argv[a + 1]) != 0;
    else if (flag == "--cg-tolerance") options.cg_tolerance = std::atof(argv[a + 1]);
    else if (flag == "--cg-memory") options.cg_memory = std::atoi(argv[a + 1]);
    else if (flag == "--preconditioner")
      options.preconditioner =
          std::string(argv[a + 1]) == "constant" ? Preconditioner::Constant : Preconditioner::GaussNewton;
    else {
      std::fprintf(stderr, "bench_models: unknown flag %s\n", flag.c_str());
      return 2;
    }
  }
  try {
    const Mesh mesh = tools::read_mesh_file(argv[1]), cage = tools::read_mesh_file(argv[2]);
    double t0 = now_ms();
    Deformer d(mesh, cage, bind);
    d.set_options(options);
    std::printf("{\"bindMs\": %.0f}\n", now_ms() - t0);
    const tools::DragScene scene = tools::drag_scene(mesh);
    d.set_handles(scene.groups);
    if (app_frames > 0) {
      app_drag(d, scene, app_frames);
      return 0;
    }
    std::vector<Vertices> shapes;
    if (integration != "reduced") shapes.push_back(run(d, scene, Integration::Full, frames));
    if (integration != "full") shapes.push_back(run(d, scene, Integration::Reduced, frames));
    if (shapes.size() == 2)
      std::printf("{\"reducedVsFull\": %.3g}\n", (shapes[0] - shapes[1]).rowwise().norm().maxCoeff() / scene.diagonal);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_models: %s\n", e.what());
    return 1;
  }
  return 0;
}
