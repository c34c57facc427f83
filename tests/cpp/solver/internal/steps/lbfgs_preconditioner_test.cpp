// The limited-memory BFGS preconditioner: the secant condition, symmetry and positive definiteness, and
// that pairs from a previous solve on a nearby matrix cut the products of the next projected PCG.
#include "core/solver/internal/steps/lbfgs_preconditioner.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "core/solver/internal/steps/projected_pcg.h"

namespace sd {
namespace {

constexpr int kM = 25;  // blocks are kM by 3

Eigen::VectorXd flat(const Eigen::MatrixXd& block) {
  return Eigen::Map<const Eigen::VectorXd>(block.data(), block.size());
}
Eigen::MatrixXd unflat(const Eigen::VectorXd& v) { return Eigen::Map<const Eigen::MatrixXd>(v.data(), kM, 3); }

Eigen::MatrixXd random_block(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd b(kM, 3);
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = normal(rng);
  return b;
}

// A symmetric positive definite 3kM x 3kM matrix with eigenvalues spread over `condition`.
Eigen::MatrixXd random_spd(double condition, std::mt19937& rng) {
  const int size = 3 * kM;
  std::normal_distribution<double> normal;
  Eigen::MatrixXd G(size, size);
  for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = normal(rng);
  const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
  Eigen::VectorXd d(size);
  for (int i = 0; i < size; ++i) d[i] = std::pow(condition, double(i) / (size - 1));
  return Q * d.asDiagonal() * Q.transpose();
}

const auto kIdentity = [](const Eigen::MatrixXd& r) { return r; };

TEST(LbfgsPreconditioner, NewestPairSatisfiesTheSecantCondition) {
  std::mt19937 rng(1);
  const Eigen::MatrixXd A = random_spd(1e3, rng);
  LbfgsPreconditioner H(4);
  for (int k = 0; k < 6; ++k) {
    const Eigen::MatrixXd s = random_block(rng);
    const Eigen::MatrixXd y = unflat(A * flat(s));
    H.add_pair(s, y);
    EXPECT_LE((H.apply(y, kIdentity) - s).norm(), 1e-10 * s.norm()) << "pair " << k;
  }
  EXPECT_EQ(H.size(), 4) << "keeps the newest `capacity` pairs";
}

TEST(LbfgsPreconditioner, IsSymmetricPositiveDefiniteAndSkipsBadPairs) {
  std::mt19937 rng(2);
  const Eigen::MatrixXd A = random_spd(1e3, rng);
  LbfgsPreconditioner H(8);
  for (int k = 0; k < 5; ++k) {
    const Eigen::MatrixXd s = random_block(rng);
    H.add_pair(s, unflat(A * flat(s)));
  }
  const Eigen::MatrixXd s = random_block(rng);
  H.add_pair(s, -s);  // negative curvature: would break positive definiteness
  H.add_pair(s, Eigen::MatrixXd::Zero(kM, 3));
  EXPECT_EQ(H.size(), 5);
  for (int k = 0; k < 5; ++k) {
    const Eigen::MatrixXd u = random_block(rng), v = random_block(rng);
    const Eigen::MatrixXd Hu = H.apply(u, kIdentity), Hv = H.apply(v, kIdentity);
    EXPECT_NEAR(v.cwiseProduct(Hu).sum(), u.cwiseProduct(Hv).sum(), 1e-10 * Hu.norm() * v.norm());
    EXPECT_GT(u.cwiseProduct(Hu).sum(), 0.0);
  }
  H.resize(0);
  EXPECT_EQ(H.size(), 0);
  const Eigen::MatrixXd u = random_block(rng);
  EXPECT_EQ(H.apply(u, kIdentity), u) << "without pairs H is the base";
}

// The textbook two-loop recursion (Nocedal and Wright, algorithm 7.4) on one block, over pairs oldest first.
Eigen::MatrixXd two_loop(const std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>>& pairs,
                         const Eigen::MatrixXd& r, const std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>& base) {
  const auto dot = [](const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); };
  std::vector<double> a(pairs.size());
  Eigen::MatrixXd q = r;
  for (size_t i = pairs.size(); i-- > 0;) {
    a[i] = dot(pairs[i].first, q) / dot(pairs[i].first, pairs[i].second);
    q -= a[i] * pairs[i].second;
  }
  Eigen::MatrixXd z = base(q);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double b = dot(pairs[i].second, z) / dot(pairs[i].first, pairs[i].second);
    z += (a[i] - b) * pairs[i].first;
  }
  return z;
}

TEST(LbfgsPreconditioner, IsTheTwoLoopRecursionForEveryBlockAndEveryCapacity) {
  // The pairs' inner products are kept and the recursion runs on several blocks at once (a step's projection
  // preconditions one block per hard constraint): the same H r as the textbook recursion block by block, through
  // the pairs' slots wrapping around, the capacity shrunk and grown with them wrapped, and set to 0 and back.
  std::mt19937 rng(4);
  const Eigen::MatrixXd A = random_spd(1e3, rng);
  const Eigen::LLT<Eigen::MatrixXd> base_llt(A + 0.5 * random_spd(10.0, rng));
  const auto base = [&](const Eigen::MatrixXd& R) {  // block-wise, as the solver's bases are
    Eigen::MatrixXd out(R.rows(), R.cols());
    for (Eigen::Index k = 0; k < R.cols() / 3; ++k)
      out.middleCols(3 * k, 3) = unflat(base_llt.solve(flat(R.middleCols(3 * k, 3))));
    return out;
  };
  const std::map<int, int> capacity_from = {{0, 5}, {9, 3}, {13, 7}, {20, 0}, {22, 4}};
  LbfgsPreconditioner H(5);
  std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> newest;  // what H should hold, oldest first
  int capacity = 5;
  for (int step = 0; step < 30; ++step) {
    if (capacity_from.count(step)) {
      capacity = capacity_from.at(step);
      H.resize(capacity);
      newest.erase(newest.begin(), newest.end() - std::min<int>(capacity, static_cast<int>(newest.size())));
    }
    const Eigen::MatrixXd s = random_block(rng);
    H.add_pair(s, unflat(A * flat(s)));
    if (capacity > 0) newest.emplace_back(s, unflat(A * flat(s)));
    if (static_cast<int>(newest.size()) > capacity) newest.erase(newest.begin());
    ASSERT_EQ(H.size(), static_cast<int>(newest.size())) << "step " << step;
    Eigen::MatrixXd blocks(kM, 9);
    for (int k = 0; k < 3; ++k) blocks.middleCols(3 * k, 3) = random_block(rng);
    const Eigen::MatrixXd together = H.apply(blocks, base);
    for (int k = 0; k < 3; ++k) {
      const Eigen::MatrixXd expected = two_loop(newest, blocks.middleCols(3 * k, 3), base);
      EXPECT_LE((together.middleCols(3 * k, 3) - expected).norm(), 1e-12 * expected.norm())
          << "step " << step << ", block " << k;
    }
  }
  // Blocks of another size (another subspace) start the memory afresh.
  const Eigen::MatrixXd small = Eigen::MatrixXd::Ones(4, 3);
  H.add_pair(small, 2.0 * small);
  EXPECT_EQ(H.size(), 1);
  EXPECT_LE((H.apply(2.0 * small, [](const Eigen::MatrixXd& r) { return r; }) - small).norm(), 1e-15)
      << "the secant condition of the one pair";
}

TEST(LbfgsPreconditioner, PairsFromANearbySolveCutTheProducts) {
  std::mt19937 rng(3);
  const Eigen::MatrixXd A0 = random_spd(1e4, rng);
  const Eigen::MatrixXd A1 = A0 + 1e-3 * random_spd(10.0, rng);  // the next Gauss-Newton matrix
  const Eigen::MatrixXd c = random_block(rng);
  LbfgsPreconditioner memory(16);
  const auto solve = [&](const Eigen::MatrixXd& A, const Eigen::MatrixXd& b, bool learn) {
    PcgOperator op;
    op.apply = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) {
      AP = unflat(A * flat(P));
      image = P;
    };
    op.precondition = [&](const Eigen::MatrixXd& R) { return memory.apply(R, kIdentity); };
    std::vector<std::pair<Eigen::MatrixXd, Eigen::MatrixXd>> pairs;
    const auto apply = op.apply;
    op.apply = [&](const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image) {
      apply(P, AP, image);
      pairs.emplace_back(P, AP);
    };
    ProjectedPcg pcg(op, b, c, 0.0, kM);
    pcg.run(1e-2, 200);
    if (learn)
      for (const auto& [P, AP] : pairs) memory.add_pair(P, AP);
    return pcg.products();
  };
  const Eigen::MatrixXd b0 = random_block(rng), b1 = b0 + 0.1 * random_block(rng);
  const int cold = solve(A1, b1, false);
  solve(A0, b0, true);
  const int warm = solve(A1, b1, false);
  std::cout << "[          ] products: " << cold << " with the base preconditioner, " << warm << " with 16 pairs\n";
  EXPECT_LT(warm, cold);
}

}  // namespace
}  // namespace sd
