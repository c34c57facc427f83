// One benchmark case of scripts/bench.mjs, shared by the native tool bench_native_cases and the
// wasm binding cpp/tools/wasm/bench_bindings.cpp, so native and wasm time exactly the same code.
//
// Scene: a capsule bar along x (length 4, radius 0.5) with about `n_target` vertices inside a bar cage
// with `cage_segments` slabs (m = 4 (segments + 1) cage vertices); the left end (x < -2.2) is fixed and
// the right end (x > 2.2) is bent by (-0.3, -1.2, 0.2), as in cpp/tools/bench_solver.
//
// Measured (ms, medians): bind (W), the streaming floor (one y = W p pass, p = m x 3), 6-column passes
// forward and transposed, one matrix-free product W^T J^T J W V (V = m x 3 and m x 6), a converged fast
// solve from rest (wall ms, products, iterations), an interactive frame (one warm-started step after a
// small drag), exact subspace / full-space / ARAP iteration costs. The result is a flat list of named
// numbers so both front ends can print it as JSON without knowing the fields.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/deformer.h"
#include "core/mesh/shapes.h"
#include "core/solver/internal/steps/subspace_step.h"
#include "core/timer.h"

namespace sd::bench {

struct CaseOptions {
  int n_target = 5000;
  int cage_segments = 24;
  int repeats = 5;         // medians of W passes and products
  int bind_repeats = 1;    // full bindings (expensive at large n)
  int solve_repeats = 1;   // converged solves from rest
  int frames = 5;          // interactive frames
  int exact_max_n = 6000;  // exact subspace only up to this many vertices (dense 3n x 3m Jacobian)
  int full_max_n = 60000;  // full-space iterations only up to this many vertices
  bool arap = true;
  bool float32 = false;  // store W in single precision (half the bytes streamed per pass)
};

using Results = std::vector<std::pair<std::string, double>>;

inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

template <typename F>
double median_ms(F&& f, int repeats) {
  std::vector<double> t;
  for (int r = 0; r < std::max(1, repeats); ++r) {
    const double t0 = now_ms();
    f();
    t.push_back(now_ms() - t0);
  }
  return median(t);
}

// Single-thread streaming read bandwidth (GB/s, median of 7): a sum over `megabytes` of doubles with four
// accumulators. The ideal floor of one W pass is W's bytes divided by this.
inline double read_bandwidth_gbs(int megabytes = 240) {
  const size_t n = static_cast<size_t>(megabytes) * 1000000 / 8 / 4 * 4;
  std::vector<double> a(n, 1.0);
  volatile double sink = 0;
  const double ms = median_ms(
      [&] {
        double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
        for (size_t i = 0; i < n; i += 4) {
          s0 += a[i];
          s1 += a[i + 1];
          s2 += a[i + 2];
          s3 += a[i + 3];
        }
        sink = sink + s0 + s1 + s2 + s3;
      },
      7);
  return (8.0 * n / 1e9) / (ms / 1e3);
}

// Capsule of length 4 and radius 0.5 with about `target` vertices (the same sizing as bench_solver).
inline Mesh capsule(int target) {
  const int segments = std::max(12, static_cast<int>(std::sqrt(target * 2.0)));
  const int rows = std::max(4, target / segments);
  const int rings = std::max(3, rows / 6);
  return make_capsule(4.0, 0.5, rings, rows - 2 * rings, segments);
}

struct Scene {
  Mesh mesh, cage;
  std::vector<std::vector<int>> groups;
  Vertices targets;
};

inline Scene bend_scene(int n_target, int cage_segments) {
  Scene s;
  s.mesh = capsule(n_target);
  s.cage = make_bar_cage(-2.7, 2.7, 0.7, 0.7, cage_segments);
  std::vector<int> left, right;
  for (int i = 0; i < s.mesh.V.rows(); ++i) {
    if (s.mesh.V(i, 0) < -2.2) left.push_back(i);
    if (s.mesh.V(i, 0) > 2.2) right.push_back(i);
  }
  s.groups = {left, right};
  s.targets.resize(static_cast<Eigen::Index>(left.size() + right.size()), 3);
  int r = 0;
  for (int v : left) s.targets.row(r++) = s.mesh.V.row(v);
  for (int v : right) s.targets.row(r++) = s.mesh.V.row(v) + Eigen::RowVector3d(-0.3, -1.2, 0.2);
  return s;
}

// The scene's handle groups and targets on a bare energy (for timing the pieces of a step one by one).
inline void set_scene_handles(DeformationEnergy& energy, const Scene& s) {
  std::vector<int> flat;
  for (const auto& g : s.groups) flat.insert(flat.end(), g.begin(), g.end());
  energy.set_handles(flat);
  energy.set_targets(s.targets);
}

inline int total_products(const StepResult& r) {
  int p = 0;
  for (const auto& it : r.iterations) p += it.products;
  return p;
}

inline int total_passes(const StepResult& r) {
  int p = 0;
  for (const auto& it : r.iterations) p += it.passes;
  return p;
}

// Median of the per-iteration ms of r, skipping the first `skip` iterations when there are more.
inline double iteration_ms(const StepResult& r, size_t skip = 1) {
  std::vector<double> t;
  for (size_t k = r.iterations.size() > skip ? skip : 0; k < r.iterations.size(); ++k) t.push_back(r.iterations[k].ms);
  return median(t);
}

inline Results run_case(const CaseOptions& o) {
  Results out;
  auto put = [&out](const std::string& k, double v) { out.emplace_back(k, v); };
  const Scene s = bend_scene(o.n_target, o.cage_segments);
  const int n = static_cast<int>(s.mesh.V.rows());
  put("n", n);
  put("m", static_cast<double>(s.cage.V.rows()));
  put("cageFaces", static_cast<double>(s.cage.F.rows()));
  int handle_count = 0;
  for (const auto& g : s.groups) handle_count += static_cast<int>(g.size());
  put("handleVertices", handle_count);
  put("float32", o.float32 ? 1 : 0);

  // Binding: the Deformer constructor binds W (MVC) and precomputes B = (L W)^T (L W).
  std::vector<double> binds, precomputes, creates;
  std::unique_ptr<Deformer> d;
  for (int r = 0; r < std::max(1, o.bind_repeats); ++r) {
    d.reset();
    const double t0 = now_ms();
    MvcOptions bind;
    bind.single_precision = o.float32;
    d = std::make_unique<Deformer>(s.mesh, s.cage, bind);
    creates.push_back(now_ms() - t0);
    binds.push_back(d->bind_ms());
    precomputes.push_back(d->precompute_ms());
  }
  const double bind_ms = median(binds);
  const double evaluations = double(n) * double(s.cage.F.rows());
  put("bindMs", bind_ms);
  put("bindEvalsPerSec", evaluations / (bind_ms / 1e3));
  put("precomputeMs", median(precomputes));
  put("createMs", median(creates));
  const BasisMatrix& W = d->basis();
  const int m = W.cols();
  put("wBytes", static_cast<double>(W.bytes()));

  double t0 = now_ms();
  d->set_handles(s.groups);
  put("setHandlesMs", now_ms() - t0);
  d->set_targets(s.targets);

  // Streaming floor and one matrix-free product, at the rest pose with the bend targets.
  {
    DeformationEnergy energy(s.mesh.V, s.mesh.F);
    set_scene_handles(energy, s);
    SubspaceStep sub(energy, W);
    sub.refactor(energy);
    const Eigen::MatrixXd P3 = s.cage.V;  // y = W p with p the cage positions
    const Eigen::MatrixXd V6 = Eigen::MatrixXd::Random(m, 6), V3 = Eigen::MatrixXd::Random(m, 3);
    const Eigen::MatrixXd R6 = Eigen::MatrixXd::Random(n, 6), R3 = Eigen::MatrixXd::Random(n, 3);
    Eigen::MatrixXd y, image;
    put("passMs", median_ms([&] { W.multiply(P3, y); }, o.repeats));
    put("pass6Ms", median_ms([&] { W.multiply(V6, y); }, o.repeats));
    put("transposePassMs", median_ms([&] { W.multiply_transpose(R3, y); }, o.repeats));
    put("transposePass6Ms", median_ms([&] { W.multiply_transpose(R6, y); }, o.repeats));
    const EnergyJacobian J = energy.jacobian(s.mesh.V);
    put("jacobianMs", median_ms([&] { energy.jacobian(s.mesh.V); }, o.repeats));
    put("evaluateMs", median_ms([&] { energy.evaluate(s.mesh.V); }, o.repeats));
    put("volumeGradientMs", median_ms([&] { energy.volume_gradient(s.mesh.V); }, o.repeats));
    put("normalProductMs", median_ms([&] { J.normal_product(R3); }, o.repeats));
    // The PCG applies the product to one m x 3 block (projected_pcg.h); 6 columns for comparison.
    put("productMs", median_ms([&] { sub.product(J, V3, image); }, o.repeats));
    put("product6Ms", median_ms([&] { sub.product(J, V6, image); }, o.repeats));
  }

  // Converged fast solve from rest (the Deformer's defaults).
  std::vector<double> solves;
  StepResult r;
  for (int k = 0; k < std::max(1, o.solve_repeats); ++k) {
    d->reset();
    t0 = now_ms();
    r = d->solve();
    solves.push_back(now_ms() - t0);
  }
  put("solveMs", median(solves));
  put("products", total_products(r));
  put("solvePasses", total_passes(r));
  put("solveIterations", static_cast<double>(r.iterations.size()));
  put("solveConverged", r.converged ? 1 : 0);
  put("solveEnergy", r.iterations.empty() ? NAN : r.iterations.back().energy);
  put("solveVolumeRelError", r.iterations.empty() ? NAN : r.iterations.back().volume_rel_error);

  // Interactive frames: the moving handle dragged by 0.01 per frame, one warm-started step each.
  {
    Vertices dragged = s.targets;
    std::vector<double> frames, products, passes;
    for (int f = 0; f < std::max(1, o.frames); ++f) {
      for (Eigen::Index k = static_cast<Eigen::Index>(s.groups[0].size()); k < dragged.rows(); ++k)
        dragged(k, 1) -= 0.01;
      d->set_targets(dragged);
      t0 = now_ms();
      const StepResult frame = d->step(1);
      frames.push_back(now_ms() - t0);
      products.push_back(total_products(frame));
      passes.push_back(total_passes(frame));
    }
    put("stepMs", median(frames));
    put("stepProducts", median(products));
    put("stepPasses", median(passes));
    d->set_targets(s.targets);
  }

  SolverOptions opt;
  if (n <= o.exact_max_n) {
    opt.jacobian = JacobianMode::Exact;
    d->set_options(opt);
    d->reset();
    put("exactIterationMs", iteration_ms(d->step(3)));
  }
  if (n <= o.full_max_n) {
    opt.method = Method::Full;
    opt.jacobian = JacobianMode::Fast;
    d->set_options(opt);
    d->reset();
    put("fullIterationMs", iteration_ms(d->step(3)));
    if (n <= o.exact_max_n) {
      opt.jacobian = JacobianMode::Exact;
      d->set_options(opt);
      d->reset();
      put("fullExactIterationMs", iteration_ms(d->step(3)));
    }
  }
  if (o.arap) {
    opt.method = Method::Arap;
    t0 = now_ms();
    d->set_options(opt);
    d->reset();
    put("arapSetupMs", now_ms() - t0);
    put("arapIterationMs", iteration_ms(d->step(6)));
  }
  return out;
}

}  // namespace sd::bench
