#include "core/skeleton/skeleton.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/geometry/ray_caster.h"
#include "core/geometry/winding_number.h"
#include "core/parallel/parallel_for.h"

namespace sd {
namespace {

[[noreturn]] void fail(const std::string& message) { throw Error(ErrorCode::InvalidSkeleton, "skeleton: " + message); }

std::string joint_name(Eigen::Index j) { return "joint " + std::to_string(j); }

// A coordinate in six significant digits (std::to_string writes 1e300 as 301 digits).
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

void check_joints(const Skeleton& s, const Mesh& mesh) {
  for (Eigen::Index j = 0; j < s.joints.rows(); ++j) {
    if (!s.joints.row(j).allFinite()) fail(joint_name(j) + " has a coordinate that is not a finite number");
    // A joint outside deforms with nothing: its coordinates would extrapolate. The winding number is 1 inside a
    // closed outward surface (also inside one component of several) and 0 outside.
    if (!(winding_number(mesh, s.joints.row(j)) > 0.5))
      fail(joint_name(j) + " at (" + number(s.joints(j, 0)) + ", " + number(s.joints(j, 1)) + ", " +
           number(s.joints(j, 2)) + ") is outside the mesh; joints must lie inside it");
  }
}

void check_bones(const Skeleton& s, double diagonal) {
  const int J = static_cast<int>(s.joints.rows());
  std::set<std::pair<int, int>> seen;
  std::vector<bool> used(static_cast<size_t>(J), false);
  for (size_t b = 0; b < s.bones.size(); ++b) {
    const auto [i, k] = s.bones[b];
    const std::string bone = "bone " + std::to_string(b);
    if (i < 0 || i >= J || k < 0 || k >= J)
      fail(bone + " joins joints " + std::to_string(i) + " and " + std::to_string(k) + ", outside [0, " +
           std::to_string(J) + ")");
    if (i == k) fail(bone + " joins " + joint_name(i) + " to itself");
    if (!seen.emplace(std::min(i, k), std::max(i, k)).second)
      fail(bone + " joins joints " + std::to_string(i) + " and " + std::to_string(k) + ", as an earlier bone does");
    if (!((s.joints.row(i) - s.joints.row(k)).norm() > 1e-6 * diagonal))
      fail(bone + " has (almost) zero length: its joints " + std::to_string(i) + " and " + std::to_string(k) +
           " coincide");
    used[static_cast<size_t>(i)] = used[static_cast<size_t>(k)] = true;
  }
  for (int j = 0; j < J; ++j)
    if (!used[static_cast<size_t>(j)]) fail(joint_name(j) + " ends no bone (remove it, or join it with a bone)");
}

// Where the segment from a to c crosses the surface, as increasing fractions of its length in (0, 1). Crossings
// closer than 1e-9 of the length are one: a segment through an edge shared by two triangles meets both there.
std::vector<double> surface_crossings(const RayCaster& rays, const Eigen::Vector3d& a, const Eigen::Vector3d& c) {
  constexpr double kSame = 1e-9;
  std::vector<double> crossings;
  // Each call starts after the last hit (t > t_min), so every triangle is met at most once and the loop ends.
  for (RayHit hit = rays.first_hit(a, c - a, 0.0, 1.0); hit.face >= 0;
       hit = rays.first_hit(a, c - a, hit.t, 1.0, hit.face))
    if (crossings.empty() || hit.t - crossings.back() > kSame) crossings.push_back(hit.t);
  return crossings;
}

// The fractions of a bone's length at which its inside is tested: its samples (skeleton_points(), what the solver
// reads along it) and the middle of every stretch between two surface crossings, in increasing order. The winding
// number is constant along a stretch, so a gap between two parts is caught however thin it is and wherever it falls
// between the samples.
std::vector<double> test_fractions(const std::vector<double>& crossings) {
  std::vector<double> fractions;
  for (int k = 0; k < kBoneSamples; ++k) fractions.push_back(bone_sample_fraction(k));
  for (size_t i = 0; i + 1 < crossings.size(); ++i) fractions.push_back(0.5 * (crossings[i] + crossings[i + 1]));
  std::sort(fractions.begin(), fractions.end());
  return fractions;
}

// Every bone inside the mesh along its whole length: two joints inside a C-shaped model, or in two parts with air
// between them, can be joined through the air, where the points' coordinates would extrapolate. A crossing of the
// surface alone is not an error (a bone may pass from one overlapping part into another, still inside); a stretch
// between crossings whose winding number is at most 1/4 is outside. A point on the surface (winding number 1/2) is
// accepted, as the points' mean value coordinates accept it. The bones are tested on the thread pool (255 bones
// against 86k faces: about 2000 winding numbers, one ray walk per bone). Returns per bone the first outside
// fraction of its length, or -1.
std::vector<double> first_outside(const Skeleton& s, const Mesh& mesh) {
  const RayCaster rays(mesh);
  const BatchWindingNumber winding(mesh);
  const int bones = static_cast<int>(s.bones.size());
  std::vector<double> outside(static_cast<size_t>(bones), -1.0);
  parallel::parallel_for(0, bones, 8, [&](int lo, int hi) {
    BatchWindingNumber::Scratch scratch;
    for (int b = lo; b < hi; ++b) {
      const Eigen::Vector3d a = s.joints.row(s.bones[static_cast<size_t>(b)][0]).transpose();
      const Eigen::Vector3d c = s.joints.row(s.bones[static_cast<size_t>(b)][1]).transpose();
      for (double f : test_fractions(surface_crossings(rays, a, c))) {
        if (winding(((1.0 - f) * a + f * c).transpose(), scratch) > 0.25) continue;
        outside[static_cast<size_t>(b)] = f;
        break;
      }
    }
  });
  return outside;
}

void check_bones_inside(const Skeleton& s, const Mesh& mesh) {
  const std::vector<double> outside = first_outside(s, mesh);
  for (size_t b = 0; b < outside.size(); ++b) {
    if (outside[b] < 0) continue;
    char where[32];
    std::snprintf(where, sizeof where, "%.3g%%", 100 * outside[b]);
    fail("bone " + std::to_string(b) + " (from joint " + std::to_string(s.bones[b][0]) + " to joint " +
         std::to_string(s.bones[b][1]) + ") leaves the mesh between its joints (at " + where +
         " of its length); a bone must lie inside the mesh");
  }
}

}  // namespace

Vertices skeleton_points(const Skeleton& s) {
  const Eigen::Index J = s.joints.rows();
  Vertices points(J + kBoneSamples * static_cast<Eigen::Index>(s.bones.size()), 3);
  points.topRows(J) = s.joints;
  for (size_t b = 0; b < s.bones.size(); ++b)
    for (int k = 0; k < kBoneSamples; ++k)
      points.row(J + kBoneSamples * static_cast<Eigen::Index>(b) + k) =
          (1.0 - bone_sample_fraction(k)) * s.joints.row(s.bones[b][0]) +
          bone_sample_fraction(k) * s.joints.row(s.bones[b][1]);
  return points;
}

double SkeletonReport::max_length_error() const {
  double e = 0;
  for (const BoneReport& b : bones) e = std::max(e, std::abs(b.length_error));
  return e;
}

double SkeletonReport::max_straightness_error() const {
  double e = 0;
  for (const BoneReport& b : bones) e = std::max(e, b.straightness_error);
  return e;
}

void validate_skeleton(const Skeleton& skeleton, const Mesh& mesh, bool mesh_is_closed) {
  if (skeleton.joints.cols() != 3) fail("joints must have 3 coordinates each");
  if (skeleton.empty() && skeleton.joints.rows() > 0) fail("joints without bones (give bones, or no joints)");
  if (skeleton.empty()) return;
  if (!mesh_is_closed)
    fail("the mesh has boundary edges (holes); a skeleton needs a closed mesh, whose coordinates carry the joints");
  check_joints(skeleton, mesh);
  check_bones(skeleton, bounding_box_diagonal(mesh.V));
  check_bones_inside(skeleton, mesh);
}

}  // namespace sd
