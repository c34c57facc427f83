// Part volumes closed by fan caps: one part is the mesh volume to the bit, the parts add up to the whole for any
// partition (loops, junctions, random patches), each is translation and rotation invariant, and the gradients
// match finite differences.
#include "core/parts/part_volume.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>

#include "core/mesh/shapes.h"
#include "core/mesh/volume.h"
#include "core/parts/partition.h"
#include "test_support.h"

namespace sd {
namespace {

using PartOf = std::function<int(const Eigen::RowVector3d& centroid)>;

std::vector<int> parts_by_centroid(const Mesh& m, const PartOf& part_of) {
  std::vector<int> parts(static_cast<size_t>(m.F.rows()));
  for (int f = 0; f < m.F.rows(); ++f)
    parts[f] = part_of((m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0);
  return parts;
}

Vertices perturbed(const Mesh& m, double amount, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-amount, amount);
  Vertices X = m.V;
  for (Eigen::Index i = 0; i < X.size(); ++i) X.data()[i] += u(rng);
  return X;
}

struct Case {
  const char* name;
  Mesh mesh;
  std::vector<int> parts;
};

// Two parts meeting along one loop; three sectors meeting at the poles; eight octants; random patches.
std::vector<Case> cases() {
  const Mesh capsule = make_capsule(2.0, 0.5, 5, 8, 14);
  const Mesh sphere = make_icosphere(3, 1.0);
  std::vector<int> random_parts(static_cast<size_t>(sphere.F.rows()));
  std::mt19937 rng(7);
  for (int& p : random_parts) p = static_cast<int>(rng() % 4);
  return {
      {"neck cut", capsule,
       parts_by_centroid(capsule, [](const Eigen::RowVector3d& c) { return c.x() > 0.3 ? 1 : 0; })},
      {"three sectors", capsule,
       parts_by_centroid(capsule,
                         [](const Eigen::RowVector3d& c) {
                           const double angle = std::atan2(c.z(), c.y()) + M_PI;
                           return std::min(2, static_cast<int>(angle / (2 * M_PI / 3)));
                         })},
      {"octants", sphere,
       parts_by_centroid(sphere,
                         [](const Eigen::RowVector3d& c) {
                           return (c.x() > 0.1 ? 1 : 0) + (c.y() > -0.2 ? 2 : 0) + (c.z() > 0.05 ? 4 : 0);
                         })},
      {"random patches", sphere, random_parts},
  };
}

// Open meshes: holes capped by fans, alone or crossing from one part to another.
std::vector<Case> open_cases() {
  const Mesh holed = test::drop_faces(make_icosphere(3, 1.0), [](const Eigen::RowVector3d& c) {
    return c.z() > 0.8 || (c.x() > 0.85 && std::abs(c.z()) < 0.3);
  });
  const Mesh tube = test::drop_faces(make_capsule(2.0, 0.5, 5, 8, 14),
                                     [](const Eigen::RowVector3d& c) { return std::abs(c.x()) > 1.1; });
  return {
      {"sphere with two holes, one part", holed, std::vector<int>(static_cast<size_t>(holed.F.rows()), 0)},
      {"sphere with two holes, halves across a hole", holed,
       parts_by_centroid(holed, [](const Eigen::RowVector3d& c) { return c.y() > 0.05 ? 1 : 0; })},
      {"open tube, three sectors", tube,
       parts_by_centroid(tube,
                         [](const Eigen::RowVector3d& c) {
                           const double angle = std::atan2(c.z(), c.y()) + M_PI;
                           return std::min(2, static_cast<int>(angle / (2 * M_PI / 3)));
                         })},
  };
}

// The volume of a mesh whose every boundary loop is closed by the fan from the loop's centroid, computed
// directly: the loops walked here from the boundary half-edges, the fans added as triangles.
double fan_closed_volume(const Vertices& X, const Faces& F) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) directed[{F(f, k), F(f, (k + 1) % 3)}] = f;
  std::map<int, int> next;  // boundary half-edges a -> b (no b -> a)
  for (const auto& entry : directed)
    if (!directed.count({entry.first.second, entry.first.first})) next[entry.first.first] = entry.first.second;
  // The open surface and its caps both about the origin (an open surface's sum depends on the point).
  double volume = signed_volume(X, F, VolumeReference::Zero());
  while (!next.empty()) {
    std::vector<int> loop;
    for (int v = next.begin()->first; next.count(v);) {
      loop.push_back(v);
      const int w = next[v];
      next.erase(v);
      v = w;
    }
    Eigen::RowVector3d c = Eigen::RowVector3d::Zero();
    for (int v : loop) c += X.row(v);
    c /= static_cast<double>(loop.size());
    for (size_t i = 0; i < loop.size(); ++i) {
      const Eigen::RowVector3d a = X.row(loop[i]), b = X.row(loop[(i + 1) % loop.size()]);
      volume += b.cross(a).dot(c) / 6.0;  // the cap triangle (b, a, c)
    }
  }
  return volume;
}

// The closed cases and the open ones.
std::vector<Case> all_cases() {
  std::vector<Case> all = cases();
  for (const Case& c : open_cases()) all.push_back(c);
  return all;
}

TEST(PartVolumes, OpenMeshIsClosedByAFanOverEachHole) {
  const Case c = open_cases()[0];
  const PartVolumes one(c.mesh.F, static_cast<int>(c.mesh.V.rows()), c.parts);
  EXPECT_EQ(one.boundary_curve_count(), 2);
  EXPECT_EQ(one.junction_count(), 0);
  const Vertices X = perturbed(c.mesh, 0.03, 4);
  const double expected = fan_closed_volume(X, c.mesh.F);
  EXPECT_NEAR(one.evaluate(X, volume_reference(X, c.mesh.F))[0], expected, 1e-13 * expected);
  // A little below the closed icosphere's volume: the flat caps cut off two thin spherical caps.
  const Mesh closed = make_icosphere(3, 1.0);
  const double whole = signed_volume(closed.V, closed.F),
               capped = one.evaluate(c.mesh.V, volume_reference(c.mesh.V, c.mesh.F))[0];
  EXPECT_LT(capped, whole);
  EXPECT_GT(capped, 0.95 * whole);
}

TEST(PartVolumes, OpenMeshPartsAreTranslationAndRotationInvariant) {
  for (const Case& c : open_cases()) {
    const PartVolumes parts(c.mesh.F, static_cast<int>(c.mesh.V.rows()), c.parts);
    EXPECT_GT(parts.boundary_curve_count(), 0) << c.name;
    const Vertices X = perturbed(c.mesh, 0.03, 5);
    const Eigen::VectorXd v = parts.evaluate(X, volume_reference(X, c.mesh.F));
    const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -0.5).normalized()).toRotationMatrix();
    const Vertices moved = (X * R.transpose()).rowwise() + Eigen::RowVector3d(-4.0, 2.0, 9.0);
    EXPECT_LE((parts.evaluate(moved, volume_reference(moved, c.mesh.F)) - v).cwiseAbs().maxCoeff(),
              1e-12 * v.cwiseAbs().sum())
        << c.name;
  }
}

// Default parts: one global volume for one closed component, one capped part for an open one, one per
// component otherwise, and a flat component shares the part of the largest.
TEST(PartVolumes, DefaultPartsAreTheComponents) {
  const Mesh sphere = make_icosphere(2, 1.0);
  EXPECT_TRUE(default_volume_parts(sphere.V, sphere.F).empty());
  const Case open = open_cases()[0];
  EXPECT_EQ(default_volume_parts(open.mesh.V, open.mesh.F),
            std::vector<int>(static_cast<size_t>(open.mesh.F.rows()), 0));
  Mesh small = make_icosphere(1, 0.3);
  small.V.col(0).array() += 3.0;
  const Mesh two = test::join_meshes(sphere, small);
  const std::vector<int> parts = default_volume_parts(two.V, two.F);
  ASSERT_EQ(parts.size(), static_cast<size_t>(two.F.rows()));
  for (int f = 0; f < two.F.rows(); ++f) EXPECT_EQ(parts[f], f < sphere.F.rows() ? 0 : 1);
  const Mesh sheet = test::drop_faces(make_box(1, 1, 1, 2), [](const Eigen::RowVector3d& c) { return c.z() < 0.49; });
  Mesh with_sheet = test::join_meshes(small, sheet);
  const std::vector<int> merged = default_volume_parts(with_sheet.V, with_sheet.F);
  EXPECT_EQ(merged, std::vector<int>(static_cast<size_t>(with_sheet.F.rows()), 0));
  // 40 spheres of growing size: the 31 largest keep their own parts, the 9 smallest share one.
  Mesh pile = make_icosphere(0, 0.1);
  for (int k = 1; k < 40; ++k) {
    Mesh next = make_icosphere(0, 0.1 + 0.01 * k);
    next.V.col(0).array() += 1.0 * k;
    pile = test::join_meshes(pile, next);
  }
  const std::vector<int> piled = default_volume_parts(pile.V, pile.F);
  EXPECT_EQ(*std::max_element(piled.begin(), piled.end()), 31);
  const int faces = static_cast<int>(make_icosphere(0, 1.0).F.rows());
  for (int k = 0; k < 9; ++k) EXPECT_EQ(piled[k * faces], piled[8 * faces]) << k;
  for (int k = 9; k < 40; ++k) EXPECT_NE(piled[k * faces], piled[8 * faces]) << k;
}

// A component is flat by its own size, not the model's: a sphere of radius 1e-3 keeps its own part beside the body
// and 20 diagonals away (measured against the whole model's box it joined the body's part there and lost its volume).
TEST(PartVolumes, ASmallComponentKeepsItsOwnPartWhereverItSits) {
  const Mesh sphere = make_icosphere(2, 1.0);
  for (double x : {1.5, 20.0, 1e3}) {
    Mesh tiny = make_icosphere(1, 1e-3);
    tiny.V.col(0).array() += x;
    const Mesh two = test::join_meshes(sphere, tiny);
    const std::vector<int> parts = default_volume_parts(two.V, two.F);
    ASSERT_EQ(parts.size(), static_cast<size_t>(two.F.rows())) << x;
    EXPECT_EQ(parts.back(), 1) << x;
    EXPECT_EQ(parts.front(), 0) << x;
  }
}

TEST(PartVolumes, OnePartIsTheMeshVolumeToTheBit) {
  const Mesh m = make_capsule(2.0, 0.5, 5, 8, 14);
  const PartVolumes one(m.F, static_cast<int>(m.V.rows()), std::vector<int>(m.F.rows(), 0));
  const Vertices X = perturbed(m, 0.05, 1);
  EXPECT_EQ(one.curve_count(), 0);
  const VolumeReference o = volume_reference(X, m.F);
  EXPECT_EQ(one.evaluate(X, o)[0], signed_volume(X, m.F));
  EXPECT_TRUE(one.gradients(X, o) == Eigen::MatrixXd(volume_gradient(X, m.F)));
}

TEST(PartVolumes, AddUpToTheWholeAndAreTranslationAndRotationInvariant) {
  for (const Case& c : cases()) {
    const PartVolumes parts(c.mesh.F, static_cast<int>(c.mesh.V.rows()), c.parts);
    const Vertices X = perturbed(c.mesh, 0.03, 2);
    const Eigen::VectorXd v = parts.evaluate(X, volume_reference(X, c.mesh.F));
    const double total = signed_volume(X, c.mesh.F);
    EXPECT_NEAR(v.sum(), total, 1e-13 * total) << c.name;
    const Eigen::Matrix3d R = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
    const Vertices moved = (X * R.transpose()).rowwise() + Eigen::RowVector3d(5.0, -3.0, 8.0);
    EXPECT_LE((parts.evaluate(moved, volume_reference(moved, c.mesh.F)) - v).cwiseAbs().maxCoeff(), 1e-12 * total)
        << c.name;
    EXPECT_GT(v.minCoeff(), 0.0) << c.name << ": every part encloses volume";
    std::cout << "[          ] " << c.name << ": " << parts.count() << " parts, " << parts.curve_count()
              << " interface curves, " << parts.junction_count() << " junctions, smallest part " << v.minCoeff() / total
              << " of the volume\n";
  }
}

// Far from the origin every part volume (caps included, over holes and between parts) and its gradient are those
// at the origin, to 1e-9 at an offset of 1e5: the triangles and caps are summed about the reference point
// (volume.h), where about the origin the terms were 1e15 times the volumes.
TEST(PartVolumes, AModelFarFromTheOriginKeepsItsDigits) {
  for (const Case& c : all_cases()) {
    const PartVolumes parts(c.mesh.F, static_cast<int>(c.mesh.V.rows()), c.parts);
    const Vertices X = perturbed(c.mesh, 0.03, 6);
    const Eigen::VectorXd v0 = parts.evaluate(X, volume_reference(X, c.mesh.F));
    const Eigen::MatrixXd G0 = parts.gradients(X, volume_reference(X, c.mesh.F));
    for (double offset : {1e3, 1e5}) {
      const Vertices far = X.rowwise() + Eigen::RowVector3d(-offset, 0.4 * offset, offset);
      const VolumeReference o = volume_reference(far, c.mesh.F);
      const double tolerance = 1e-14 * offset;
      EXPECT_LE((parts.evaluate(far, o) - v0).cwiseAbs().maxCoeff(), tolerance * v0.cwiseAbs().sum())
          << c.name << " at " << offset;
      EXPECT_LE((parts.gradients(far, o) - G0).cwiseAbs().maxCoeff(), tolerance * G0.cwiseAbs().maxCoeff())
          << c.name << " at " << offset;
    }
  }
}

TEST(PartVolumes, NeckCutSplitsASymmetricCapsuleExactly) {
  // Cut at x = 0 along a ring: each half is exactly half (the cap is the same flat fan for both).
  const Mesh m = make_capsule(2.0, 0.5, 5, 8, 14);  // 8 cylinder rings: a ring of vertices at x = 0
  const std::vector<int> halves = parts_by_centroid(m, [](const Eigen::RowVector3d& c) { return c.x() > 0 ? 1 : 0; });
  const PartVolumes parts(m.F, static_cast<int>(m.V.rows()), halves);
  EXPECT_EQ(parts.curve_count(), 1);
  EXPECT_EQ(parts.junction_count(), 0);
  const Eigen::VectorXd v = parts.evaluate(m.V, volume_reference(m.V, m.F));
  EXPECT_NEAR(v[0], v[1], 1e-13 * v.sum());
}

TEST(PartVolumes, GradientsMatchFiniteDifferences) {
  for (const Case& c : all_cases()) {
    const PartVolumes parts(c.mesh.F, static_cast<int>(c.mesh.V.rows()), c.parts);
    const Vertices X = perturbed(c.mesh, 0.03, 3);
    const VolumeReference o = volume_reference(X, c.mesh.F);
    const Eigen::MatrixXd G = parts.gradients(X, o);
    ASSERT_EQ(G.cols(), 3 * parts.count());
    // Along one coordinate of one vertex a part volume is at most quadratic (each cap term is multilinear in its
    // three points, and a vertex enters at most two of them: itself and a centroid), so central differences are
    // exact but for rounding, which a large h keeps small.
    const double h = 1e-3;
    double worst = 0;
    for (Eigen::Index i = 0; i < X.rows(); ++i)
      for (int a = 0; a < 3; ++a) {
        Vertices Xp = X, Xm = X;
        Xp(i, a) += h;
        Xm(i, a) -= h;
        const Eigen::VectorXd fd = (parts.evaluate(Xp, o) - parts.evaluate(Xm, o)) / (2 * h);
        for (int k = 0; k < parts.count(); ++k) worst = std::max(worst, std::abs(fd[k] - G(i, 3 * k + a)));
      }
    EXPECT_LE(worst, 1e-9 * G.cwiseAbs().maxCoeff()) << c.name;
    std::cout << "[          ] " << c.name
              << ": max |FD - gradient| / max |gradient| = " << worst / G.cwiseAbs().maxCoeff() << "\n";
  }
}

}  // namespace
}  // namespace sd
