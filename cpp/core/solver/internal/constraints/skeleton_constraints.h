// The skeleton's hard constraints on the mesh positions X (docs/method.md section 5.4).
//
// Points inside the mesh follow it by the mesh's own mean value coordinates: a point q is q(X) = m_q^T X, with m_q
// the row of q's coordinates with respect to the rest mesh taken as a closed cage (so q(X0) = q exactly). In the
// subspace, X = X0 + W (U - U0) makes that q = q0 + (W^T m_q)^T (U - U0): a fixed combination of the cage
// vertices with the same linear precision, one form for every space. The points are the joints, then seven
// samples per bone at 1/8, 2/8, ..., 7/8 of it.
//
// Per bone b from joint a to joint c, rest length L_b:
//   length:   g = |q_c - q_a| - L_b                        (nonlinear; gradient (e_c - e_a) (x) u, u the unit bone)
//   straight: g = q_m - (q_a + q_c) / 2                        (three rows; linear: the middle sample stays the
//             middle of the segment)
// The seven samples' largest distance from the segment is the report's straightness error: the middle is held, the
// others follow the energy, so a limb may curve a little towards its joints (docs/method.md section 5.4 says why
// three held samples are worse). The middle is held only where the space of the step can represent it
// independently of the other constraints (representable()); a coarse cage may not, and that bone is then only as
// straight as its length and the energy keep it (held_samples 0).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/mesh/mesh.h"
#include "core/skeleton/skeleton.h"

namespace sd {

class SkeletonConstraints {
 public:
  static constexpr int kSamplesPerBone = kBoneSamples;
  // mesh: the rest mesh the solver uses (closed; validate_skeleton first). O(#points #triangles).
  SkeletonConstraints(const Skeleton& skeleton, const Mesh& mesh);

  const Skeleton& skeleton() const { return skeleton_; }
  int bone_count() const { return static_cast<int>(skeleton_.bones.size()); }
  // m_q for every point q, as columns: #V by (J + 7B).
  const Eigen::MatrixXd& point_rows() const { return rows_; }
  // W^T m_q (m by #points): the points' rows in the subspace of the basis W. One pass over W on first use, then
  // kept with the skeleton, so the session's check of what the subspace can hold (representable()) and the
  // subspace's steps share it. W must be the session's whole basis (#V rows), not a reduced rule's sampled rows; it is
  // known by its address, so it must not be reassigned in place while this skeleton lives (the session's never is).
  const Eigen::MatrixXd& rows_in(const BasisMatrix& W) const;
  // The points at X: (J + 7B) by 3 (rows^T X).
  Eigen::MatrixXd points(const Vertices& X) const;

  // The samples' offsets from their places on their bones, q_bk - (1 - t_k) q_a - t_k q_c with t_k = (k + 1) / 8, as
  // combinations of the points: #points by 7B, one column per sample (bone by bone). The soft straightness term of
  // the energy (deformation_energy.h) is built on them.
  const Eigen::MatrixXd& offset_combinations() const { return offset_combinations_; }
  // The offsets at the points (7B by 3), less those at rest: exactly zero at rest (the points' coordinates reproduce
  // the rest samples only to about 1e-11).
  Eigen::MatrixXd offsets(const Eigen::MatrixXd& points) const;
  // The offsets' rows on the mesh, point_rows() times offset_combinations(): #V by 7B, made on first use (only the
  // straightness term needs them).
  const Eigen::MatrixXd& offset_rows() const;
  // The same in the subspace of W: rows_in(W) times offset_combinations(), m by 7B (kept with rows_in(W)).
  const Eigen::MatrixXd& offset_rows_in(const BasisMatrix& W) const;

  // Whether each bone holds its middle sample (1) or not (0); 1 for every bone at first.
  void keep_straight(const std::vector<int>& held_per_bone);
  const std::vector<int>& held_samples() const { return held_; }
  // Per bone, whether its middle can be held: greedily in bone order, 1 where that leaves the constraints'
  // gradients linearly independent in a space whose point rows are `rows` (#V by p for X itself, W^T m_q for the
  // subspace), else 0. Throws sd::Error (InvalidSkeleton) naming the first bone whose length depends on those before
  // it there (`subspace`: whether the rows are a subspace's, which decides the remedy the message gives).
  std::vector<int> representable(const Eigen::MatrixXd& rows, bool subspace) const;

  // B lengths, then 3 rows per held middle.
  int count() const;
  // Whether constraint k is linear in the points (a held middle's row), so that a step keeps it exactly.
  bool is_linear(int k) const { return constraints_[static_cast<size_t>(k)].axis >= 0; }
  Eigen::VectorXd values(const Eigen::MatrixXd& points) const;
  // The gradients in the space whose point rows are `rows` (r by p): r by 3 count(), 3 columns per constraint.
  Eigen::MatrixXd gradients(const Eigen::MatrixXd& points, const Eigen::MatrixXd& rows) const;
  // d g_k / d t_l where the points move by `motion` per unit t_l (#points by 3L): count() by L.
  Eigen::MatrixXd slopes(const Eigen::MatrixXd& points, const Eigen::MatrixXd& motion) const;
  // What a relative error divides each constraint by: its bone's rest length.
  const Eigen::VectorXd& scales() const { return scales_; }
  // At the given points; lambda: this set's multipliers (count() entries, or empty).
  SkeletonReport report(const Eigen::MatrixXd& points, const Eigen::VectorXd& lambda = {}) const;

 private:
  // One constraint: sum_q coefficient_q q(X) . direction (a length's direction is its unit bone at X).
  struct Row {
    int bone;
    int sample;  // which of the bone's samples a straightness row holds
    int axis;    // 0-2 for a straightness row, -1 for the length
  };
  static std::vector<Row> straightness_rows(int bone, int held);
  void rebuild_rows();
  Eigen::VectorXd coefficients(const Row& row) const;  // over the points
  Eigen::RowVector3d direction(const Row& row, const Eigen::MatrixXd& points) const;
  int sample(int bone, int k) const { return static_cast<int>(skeleton_.joints.rows()) + kSamplesPerBone * bone + k; }
  // rows times offset_combinations_ (rows: r by #points), three columns per sample: O(r 7B), not O(r #points 7B).
  Eigen::MatrixXd times_offset_combinations(const Eigen::MatrixXd& rows) const;

  Skeleton skeleton_;
  Eigen::MatrixXd rows_;
  mutable const BasisMatrix* rows_basis_ = nullptr;  // the basis rows_in() was last asked for
  mutable Eigen::MatrixXd basis_rows_;               // and its W^T m_q
  mutable Eigen::MatrixXd basis_offset_rows_;        // and its W^T m_q times offset_combinations_
  Eigen::MatrixXd offset_combinations_;
  Eigen::MatrixXd rest_offsets_;
  mutable Eigen::MatrixXd offset_rows_;  // empty until offset_rows() is first asked for
  Eigen::VectorXd rest_lengths_;
  std::vector<int> held_;
  std::vector<Row> constraints_;
  Eigen::VectorXd scales_;
};

}  // namespace sd
