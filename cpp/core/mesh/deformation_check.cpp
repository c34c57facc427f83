#include "core/mesh/deformation_check.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "core/geometry/self_intersection.h"

namespace sd {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFoldAngle = kPi / 2;         // extra bend of an edge that counts as a fold
constexpr double kCollapsedAreaRatio = 1e-12;  // deformed / rest area below this: collapsed
constexpr double kOnSurfaceRatio = 1e-9;       // the intersection tests' tolerance, as the rest cage's check
constexpr double kFoldedFlatCos = -1 + 1e-10;  // only faces folded flat onto each other count as crossing
constexpr int kMaxPairs = 100;
constexpr size_t kShown = 5;

Eigen::RowVector3d face_normal(const Vertices& X, const Faces& F, int f) {
  return (X.row(F(f, 1)) - X.row(F(f, 0))).cross(X.row(F(f, 2)) - X.row(F(f, 0)));
}

// Signed angle between the normals of f and g across their edge a -> b (as f walks it): positive where the
// surface bends outward (convex).
double bend(const Vertices& X, const Faces& F, int f, int g, int a, int b) {
  const Eigen::RowVector3d nf = face_normal(X, F, f), ng = face_normal(X, F, g);
  const Eigen::RowVector3d e = (X.row(b) - X.row(a)).normalized();
  return std::atan2(nf.cross(ng).dot(e), nf.dot(ng));
}

std::string first_few(const std::vector<int>& items, const IndexNames* names) {
  std::string out;
  for (size_t i = 0; i < items.size() && i < kShown; ++i)
    out += (i ? ", " : "") + std::to_string(names ? names->face[items[i]] : items[i]);
  if (items.size() > kShown) out += " ...";
  return out;
}

}  // namespace

FoldCount folded_triangles(const Mesh& rest, const Vertices& X) {
  const Faces& F = rest.F;
  const long long n = rest.V.rows();
  std::unordered_map<long long, int> face_of;  // directed edge a -> b: its face
  face_of.reserve(static_cast<size_t>(3 * F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) face_of[F(f, k) * n + F(f, (k + 1) % 3)] = f;
  std::vector<char> folded(static_cast<size_t>(F.rows()), 0);
  for (int f = 0; f < F.rows(); ++f) {
    const double rest_area = face_normal(rest.V, F, f).norm(), area = face_normal(X, F, f).norm();
    if (!(area > kCollapsedAreaRatio * rest_area)) folded[f] = 1;
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      const auto across = face_of.find(b * n + a);
      if (across == face_of.end() || across->second < f) continue;  // each interior edge once
      const int g = across->second;
      double turn = bend(X, F, f, g, a, b) - bend(rest.V, F, f, g, a, b);
      turn = std::remainder(turn, 2 * kPi);  // into [-pi, pi]
      if (std::abs(turn) > kFoldAngle) folded[f] = folded[g] = 1;
    }
  }
  FoldCount out;
  for (int f = 0; f < F.rows(); ++f)
    if (folded[f]) {
      ++out.folded_triangles;
      if (out.first.size() <= kShown) out.first.push_back(f);
    }
  return out;
}

std::vector<Finding> check_deformation(const Mesh& rest, const Vertices& X, const Mesh& rest_cage, const Vertices& P,
                                       const IndexNames* names) {
  std::vector<Finding> findings;
  const FoldCount folds = folded_triangles(rest, X);
  if (folds.folded_triangles > 0)
    findings.push_back({Severity::Warning, "folded_triangles",
                        "the deformed mesh folds over: " + std::to_string(folds.folded_triangles) + " of " +
                            std::to_string(rest.F.rows()) + " triangles turned over against a neighbour or collapsed " +
                            "(first: " + first_few(folds.first, names) +
                            "); smaller handle motions or more handles avoid it"});
  if (rest_cage.F.rows() > 0 && P.rows() == rest_cage.V.rows() && P.allFinite()) {
    const Mesh deformed{P, rest_cage.F};
    const auto pairs =
        self_intersections(deformed, kOnSurfaceRatio * bounding_box_diagonal(P), kMaxPairs, kFoldedFlatCos);
    if (!pairs.empty())
      findings.push_back(
          {Severity::Warning, "cage_self_intersecting",
           "the deformed cage crosses itself: " + std::string(pairs.size() >= size_t(kMaxPairs) ? "at least " : "") +
               std::to_string(pairs.size()) + " pairs of its faces intersect (first: faces " +
               std::to_string(pairs[0].first) + " and " + std::to_string(pairs[0].second) +
               "); the mesh follows a folded cage unpredictably there"});
  }
  return findings;
}

}  // namespace sd
