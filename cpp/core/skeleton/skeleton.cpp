#include "core/skeleton/skeleton.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
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

// Every bone's samples (skeleton_points(), what the solver reads along it) inside the mesh too: two joints inside a
// C-shaped model can be joined through the air, where the points' coordinates would extrapolate. A sample on the
// surface (winding number 1/2) is accepted, as the points' mean value coordinates accept it; outside, the winding
// number is 0. The samples are tested together on the thread pool (255 bones against 86k faces: 1.5e8 solid angles).
void check_bones_inside(const Skeleton& s, const Mesh& mesh) {
  const Vertices points = skeleton_points(s);
  const int J = static_cast<int>(s.joints.rows()), count = static_cast<int>(points.rows()) - J;
  const BatchWindingNumber winding(mesh);
  std::vector<unsigned char> outside(static_cast<size_t>(count), 0);
  parallel::parallel_for(0, count, 64, [&](int lo, int hi) {
    BatchWindingNumber::Scratch scratch;
    for (int q = lo; q < hi; ++q) outside[static_cast<size_t>(q)] = !(winding(points.row(J + q), scratch) > 0.25);
  });
  for (int q = 0; q < count; ++q) {
    if (!outside[static_cast<size_t>(q)]) continue;
    const size_t b = static_cast<size_t>(q / kBoneSamples);
    fail("bone " + std::to_string(b) + " (from joint " + std::to_string(s.bones[b][0]) + " to joint " +
         std::to_string(s.bones[b][1]) + ") leaves the mesh between its joints (at " +
         std::to_string(q % kBoneSamples + 1) + "/8 of its length); a bone must lie inside the mesh");
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
