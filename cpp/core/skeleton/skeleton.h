// A skeleton: joints (points inside the mesh at rest) and bones (pairs of joints), the figure's rigid limbs
// (docs/method.md section 5.4). The solver keeps each bone's length and keeps it straight (skeleton_constraints.h);
// this file holds the value, the points it is read at and its checks.
#pragma once

#include <array>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct Skeleton {
  Vertices joints = Vertices(0, 3);       // J by 3, rest positions, strictly inside the mesh
  std::vector<std::array<int, 2>> bones;  // joint indices; a joint may end several bones
  bool empty() const { return bones.empty(); }
};

// The points the solver reads along a skeleton: the joints, then kBoneSamples samples per bone, sample k of a bone at
// bone_sample_fraction(k) = (k + 1) / 8 of the way from its first joint to its second.
constexpr int kBoneSamples = 7;
inline double bone_sample_fraction(int k) { return (k + 1) / 8.0; }
Vertices skeleton_points(const Skeleton& skeleton);

// What a solve made of a skeleton (Deformer::skeleton_report).
struct BoneReport {
  double length = 0;              // |q_c - q_a| at X
  double length_error = 0;        // (length - L) / L
  double straightness_error = 0;  // largest distance of its seven samples from the segment, / L
  double lambda = 0;              // the length constraint's multiplier (0 when none is known)
  int held_samples = 1;           // 1: its middle sample is held on the segment; 0: the space cannot hold it
  bool straight_hard = true;      // held_samples == 1
};

struct SkeletonReport {
  Vertices joints = Vertices(0, 3);  // deformed joints, J by 3
  std::vector<BoneReport> bones;
  // false under a method that ignores the skeleton (ARAP): the errors are measured, and each bone says it held
  // nothing (lambda 0, held_samples 0, straight_hard false).
  bool kept = true;
  double max_length_error() const;
  double max_straightness_error() const;
};

// Throws sd::Error (ErrorCode::InvalidSkeleton) naming the first problem: joints that are not finite or lie
// outside the closed mesh (winding number below 1/2), a bone with an index out of range, a bone from a joint to
// itself, the same bone twice, a bone shorter than 1e-6 of the mesh's bounding-box diagonal, joints no bone uses,
// a bone that leaves the mesh between its joints (any stretch of the segment between two crossings of the surface
// outside, however short), or a mesh with boundary edges (a joint's coordinates need a closed surface).
void validate_skeleton(const Skeleton& skeleton, const Mesh& mesh, bool mesh_is_closed);

}  // namespace sd
