// Benchmark of the mean value coordinates binding and of the W products (native; the wasm numbers come
// from scripts/bench/mvc.mjs on the same cases). Points: a capsule surface inside a subdivided bar cage
// (~300 cage vertices), at n = 5k, 20k, 50k by default.
//   build/<dir>/bench_mvc [n ...] [--cage-segments S] [--float32]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "core/timer.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/mesh/shapes.h"

namespace {

using sd::now_ms;

// About n points: the vertices of a capsule of radius 0.45, length 2 (inside the cage [-1.7,1.7] x [-0.7,0.7]^2).
sd::Vertices capsule_points(int n) {
  // capsule vertex count = 2 + (2 rings + cyl - 1) * segments; pick segments ~ sqrt(n / 2).
  int segments = std::max(8, static_cast<int>(std::sqrt(n / 2.0)));
  int rings = std::max(2, segments / 4);
  int cylinder = std::max(1, (n - 2) / segments - 2 * rings + 1);
  return sd::make_capsule(2.0, 0.45, rings, cylinder, segments).V;
}

// CPU time of this thread: the machine may be shared, so wall time alone overstates the cost.
double cpu_ms() { return 1e3 * double(std::clock()) / CLOCKS_PER_SEC; }

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sizes;
  int subdivisions = 7;  // 6 * 7^2 + 2 = 296 vertices
  bool single = false;
  for (int a = 1; a < argc; ++a) {
    if (!std::strcmp(argv[a], "--cage-subdivisions") && a + 1 < argc) subdivisions = std::atoi(argv[++a]);
    else if (!std::strcmp(argv[a], "--float32")) single = true;
    else sizes.push_back(std::atoi(argv[a]));
  }
  if (sizes.empty()) sizes = {5000, 20000, 50000};
  sd::Mesh cage = sd::make_box(3.4, 1.4, 1.4, subdivisions);
  std::printf("cage: %d vertices, %d triangles; storage %s\n", int(cage.V.rows()), int(cage.F.rows()),
              single ? "float32" : "float64");
  for (int n : sizes) {
    sd::Vertices points = capsule_points(n);
    sd::MvcOptions options;
    options.single_precision = single;
    options.memory_budget_bytes = std::size_t(4) << 30;
    sd::MvcReport report;
    double t0 = now_ms(), c0 = cpu_ms();
    sd::BasisMatrix W = sd::mean_value_coordinates(points, cage, options, &report);
    double bind_ms = now_ms() - t0, bind_cpu = cpu_ms() - c0;
    // Products with k = 4 columns (x, y, z and the volume gradient), median of 5.
    Eigen::MatrixXd P = Eigen::MatrixXd::Random(W.cols(), 4), R = Eigen::MatrixXd::Random(W.rows(), 4), out;
    std::vector<double> mul, mult;
    for (int rep = 0; rep < 5; ++rep) {
      double a = now_ms();
      W.multiply(P, out);
      double b = now_ms();
      W.multiply_transpose(R, out);
      double c = now_ms();
      mul.push_back(b - a);
      mult.push_back(c - b);
    }
    std::sort(mul.begin(), mul.end());
    std::sort(mult.begin(), mult.end());
    std::printf(
        "n=%6d m=%d: bind %7.1f ms wall (%7.1f ms cpu), %5.1f M evals/s wall (%5.1f cpu), min weight %.3g, "
        "W %.1f MB; W*P(k=4) %.2f ms, W^T*R(k=4) %.2f ms\n",
        int(points.rows()), int(W.cols()), bind_ms, bind_cpu, report.evaluations / (bind_ms * 1e3),
        report.evaluations / (bind_cpu * 1e3), report.min_weight, W.bytes() / 1e6, mul[2], mult[2]);
  }
  return 0;
}
