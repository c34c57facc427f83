// Automatic volume parts (spectral embedding + k-means): a long capsule splits across its length, parts are
// face-connected, the result is deterministic, and a real model gets K connected parts.
#include "core/parts/auto_partition.h"

#include <gtest/gtest.h>

#include <climits>
#include <map>
#include <set>

#include "core/mesh/shapes.h"
#include "core/parts/part_volume.h"
#include "core/parts/partition.h"
#include "test_support.h"

namespace sd {
namespace {

double centroid_x(const Mesh& m, int f) { return (m.V(m.F(f, 0), 0) + m.V(m.F(f, 1), 0) + m.V(m.F(f, 2), 0)) / 3.0; }

// Whether part p's triangles are face-connected (across edges).
bool connected(const Mesh& m, const std::vector<int>& part, int p) {
  std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
  int count = 0, first = -1;
  for (int f = 0; f < m.F.rows(); ++f) {
    if (part[f] != p) continue;
    ++count;
    if (first < 0) first = f;
    for (int k = 0; k < 3; ++k) faces_of_edge[std::minmax(m.F(f, k), m.F(f, (k + 1) % 3))].push_back(f);
  }
  std::set<int> seen{first};
  std::vector<int> stack{first};
  while (!stack.empty()) {
    const int f = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k)
      for (int g : faces_of_edge[std::minmax(m.F(f, k), m.F(f, (k + 1) % 3))])
        if (seen.insert(g).second) stack.push_back(g);
  }
  return static_cast<int>(seen.size()) == count;
}

TEST(AutoParts, ALongCapsuleSplitsAcrossItsLength) {
  const Mesh capsule = make_capsule(4.0, 0.5, 6, 16, 16);
  for (int K : {2, 3}) {
    const std::vector<int> part = auto_parts(capsule, K);
    ASSERT_EQ(validate_parts(part, static_cast<int>(capsule.F.rows())), K);
    std::vector<std::pair<double, int>> by_x;
    for (int f = 0; f < capsule.F.rows(); ++f) by_x.push_back({centroid_x(capsule, f), part[f]});
    std::sort(by_x.begin(), by_x.end());
    const double length = by_x.back().first - by_x.front().first;
    const PartVolumes volumes(capsule.F, static_cast<int>(capsule.V.rows()), part);
    const Eigen::VectorXd v = volumes.evaluate(capsule.V, volume_reference(capsule.V, capsule.F));
    EXPECT_GE(v.minCoeff(), 0.5 * v.sum() / K) << "K = " << K << ": no part much smaller than the others";
    for (int p = 0; p < K; ++p) EXPECT_TRUE(connected(capsule, part, p)) << "K = " << K << " part " << p;
    // The cuts run across the capsule: the parts are slabs along x, their x ranges overlapping only at the cuts.
    std::vector<double> lo(K, 1e9), hi(K, -1e9);
    for (const auto& [x, p] : by_x) {
      lo[p] = std::min(lo[p], x);
      hi[p] = std::max(hi[p], x);
    }
    double overlap = 0;
    for (int p = 0; p < K; ++p)
      for (int q = p + 1; q < K; ++q) overlap = std::max(overlap, std::min(hi[p], hi[q]) - std::max(lo[p], lo[q]));
    EXPECT_LE(overlap, 0.15 * length) << "K = " << K;
  }
}

TEST(AutoParts, PartsAreConnectedAndTheResultIsDeterministic) {
  const Mesh torus = make_torus(1.0, 0.35, 48, 16);
  const std::vector<int> a = auto_parts(torus, 5), b = auto_parts(torus, 5);
  EXPECT_EQ(a, b);
  const int K = validate_parts(a, static_cast<int>(torus.F.rows()));
  EXPECT_EQ(K, 5);
  for (int p = 0; p < K; ++p) EXPECT_TRUE(connected(torus, a, p)) << "part " << p;
  EXPECT_EQ(auto_parts(torus, 1), std::vector<int>(torus.F.rows(), 0));
  test::expect_error([&] { auto_parts(torus, 0); }, "from 1 to");
}

TEST(AutoParts, ARealModelGetsConnectedParts) {
  SD_REQUIRE_SHARED_DATA("armadillo.obj");
  const Mesh armadillo = test::load_shared_mesh("armadillo.obj");
  const std::vector<int> part = auto_parts(armadillo, 6);
  const int K = validate_parts(part, static_cast<int>(armadillo.F.rows()));
  EXPECT_EQ(K, 6);
  const PartVolumes volumes(armadillo.F, static_cast<int>(armadillo.V.rows()), part);
  const Eigen::VectorXd v = volumes.evaluate(armadillo.V, volume_reference(armadillo.V, armadillo.F));
  std::cout << "[          ] armadillo, 6 parts: volume shares " << (v / v.sum()).transpose() << "\n";
  EXPECT_GT(v.minCoeff(), 0.0);
  for (int p = 0; p < K; ++p) EXPECT_TRUE(connected(armadillo, part, p)) << "part " << p;
}

// K + 3 eigenpairs: K near INT_MAX used to overflow into a negative count; the message names what was asked.
TEST(AutoParts, RefusesMoreThanTheMostPartsAndHugeCountsByName) {
  const Mesh capsule = make_capsule(1.0, 0.3, 24, 8, 12);
  test::expect_error([&] { auto_parts(capsule, INT_MAX); }, "got 2147483647");
  test::expect_error([&] { auto_parts(capsule, kMaxVolumeParts + 1); },
                     "at most " + std::to_string(kMaxVolumeParts) + " for any mesh");
  test::expect_error([&] { auto_parts(capsule, 0); }, "got 0");
}

}  // namespace
}  // namespace sd
