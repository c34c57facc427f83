// Anderson acceleration on fixed-point maps with known fixed points: a slowly contracting linear map
// (where plain iteration needs hundreds of steps) and a mildly nonlinear one.
#include "core/arap/internal/anderson_acceleration.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <random>

namespace sd {
namespace {

// Iterations until |x - x*| < tolerance (or the cap), with acceleration depth `depth`.
int iterations_to_converge(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& G,
                           const Eigen::VectorXd& fixed, int depth, double tolerance = 1e-10, int cap = 5000) {
  AndersonAcceleration aa(depth);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(fixed.size());
  for (int k = 1; k <= cap; ++k) {
    x = aa.next(x, G(x));
    if ((x - fixed).norm() < tolerance) return k;
  }
  return cap;
}

TEST(AndersonAcceleration, SolvesASlowLinearContractionInFewIterations) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n = 40;
  // G(x) = M x + b with eigenvalues of M in [0, 0.98]: plain iteration contracts by 0.98 per step.
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::Random(n, n)).householderQ();
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) d[i] = 0.98 * u(rng);
  d[0] = 0.98;
  const Eigen::MatrixXd M = Q * d.asDiagonal() * Q.transpose();
  const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
  const Eigen::VectorXd fixed = (Eigen::MatrixXd::Identity(n, n) - M).lu().solve(b);
  const auto G = [&](const Eigen::VectorXd& x) { return Eigen::VectorXd(M * x + b); };
  const int plain = iterations_to_converge(G, fixed, 0);
  const int accelerated = iterations_to_converge(G, fixed, 6);
  std::cout << "[          ] linear contraction 0.98: " << plain << " plain iterations, " << accelerated
            << " accelerated\n";
  EXPECT_GT(plain, 1000);
  EXPECT_LT(accelerated, plain / 5);  // measured 149 vs 1206
}

TEST(AndersonAcceleration, ConvergesOnANonlinearMapAndResetRestartsFromPlainSteps) {
  // Componentwise x_i = 0.9 cos(x_i) + 0.05 i: a contraction with a unique fixed point.
  const int n = 10;
  const auto G = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd y(n);
    for (int i = 0; i < n; ++i) y[i] = 0.9 * std::cos(x[i]) + 0.05 * i;
    return y;
  };
  Eigen::VectorXd fixed = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < 2000; ++k) fixed = G(fixed);  // plain iteration, long enough to be exact
  EXPECT_LT(iterations_to_converge(G, fixed, 5), iterations_to_converge(G, fixed, 0));

  AndersonAcceleration aa(5);
  const Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 0.3);
  aa.next(x, G(x));
  aa.reset();
  EXPECT_EQ(aa.next(x, G(x)), G(x)) << "without history the next point is G(x)";
  AndersonAcceleration off(0);
  EXPECT_EQ(off.next(x, G(x)), G(x)) << "depth 0 is plain iteration";
}

}  // namespace
}  // namespace sd
