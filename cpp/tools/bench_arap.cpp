// Benchmark of the ARAP baseline (native; wasm numbers come from the JS side on the same cases).
// Mesh: a capsule (length 4, radius 0.5) of about n vertices, n = 5k, 20k, 50k by default; handles are
// the tips of the two caps (|x| > 2.25), the right one turned 90 degrees about z (a bend). Reports the setup
// (cotangent weights), the factorization of set_handles, and the median wall and CPU time of one
// local-global iteration, plus the CPU time of one local step alone (energy(): SVDs + energy sum).
//   build/<dir>/bench_arap [n ...] [--iterations K]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include <Eigen/Geometry>

#include "core/arap/arap.h"
#include "core/mesh/shapes.h"
#include "core/timer.h"

namespace {

using sd::now_ms;

// CPU time of this process: the machine may be shared, so wall time alone can overstate the cost.
double cpu_ms() { return 1e3 * double(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// About n vertices: capsule vertex count = 2 + (2 rings + cylinder - 1) * segments.
sd::Mesh capsule(int n) {
  const int segments = std::max(8, static_cast<int>(std::sqrt(n / 1.5)));
  const int rings = std::max(2, segments / 4);
  const int cylinder = std::max(1, (n - 2) / segments - 2 * rings + 1);
  return sd::make_capsule(4.0, 0.5, rings, cylinder, segments);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int iterations = 10;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--iterations") && a + 1 < argc) iterations = std::max(1, std::atoi(argv[++a]));
    else sizes.push_back(std::atoi(argv[a]));
  }
  if (sizes.empty()) sizes = {5000, 20000, 50000};
  std::printf("ARAP on a capsule bend, native, %d iterations per size (median ms)\n", iterations);
  std::printf("%8s %8s %8s %9s %9s %10s %10s %10s %12s %12s\n", "n", "faces", "handles", "setup", "factor", "iter wall",
              "iter cpu", "local cpu", "E(iter 1)", "E(last)");
  for (int n : sizes) {
    const sd::Mesh m = capsule(n);
    double t0 = now_ms();
    sd::ArapSolver arap(m.V, m.F);
    const double setup = now_ms() - t0;
    std::vector<int> handles;
    for (int i = 0; i < m.V.rows(); ++i)
      if (std::abs(m.V(i, 0)) > 2.25) handles.push_back(i);
    arap.set_handles(handles);
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    sd::Vertices targets(static_cast<int>(handles.size()), 3);
    for (size_t k = 0; k < handles.size(); ++k) {
      Eigen::Vector3d p = m.V.row(handles[k]).transpose();
      if (p.x() > 0) p = Q * (p - Eigen::Vector3d(2.0, 0, 0)) + Eigen::Vector3d(1.0, 1.0, 0);
      targets.row(static_cast<int>(k)) = p.transpose();
    }
    sd::Vertices X = m.V;
    std::vector<double> wall, cpu;
    double first = 0, last = 0;
    for (int it = 0; it < iterations; ++it) {
      const double c0 = cpu_ms();
      const sd::IterationStats s = arap.iterate(X, targets);
      cpu.push_back(cpu_ms() - c0);
      wall.push_back(s.ms);
      if (it == 0) first = s.energy;
      last = s.energy;
    }
    std::vector<double> local_cpu;
    for (int r = 0; r < 3; ++r) {
      const double c0 = cpu_ms();
      arap.energy(X);
      local_cpu.push_back(cpu_ms() - c0);
    }
    const double local = median(local_cpu);
    std::printf("%8d %8d %8d %9.1f %9.1f %10.2f %10.2f %10.2f %12.5g %12.5g\n", int(m.V.rows()), int(m.F.rows()),
                int(handles.size()), setup, arap.factorization_ms(), median(wall), median(cpu), local, first, last);
  }
  return 0;
}
