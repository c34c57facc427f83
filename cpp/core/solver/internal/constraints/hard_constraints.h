// The hard constraints one solve keeps (docs/method.md section 6): the volume's (the global volume, or one per
// volume part) when SolverOptions::volume is on, then the skeleton's (skeleton_constraints.h: bone lengths and
// midpoints), always. One list of K constraints g_k(X) = 0 for the step (its K multipliers and the Schur complement
// of constrained_step.h), the line search's merit 1/2 |f|^2 + lambda . g and the restoration after each step, so
// every kind is treated alike in the subspace and the full space, with full or reduced integration.
//
// Each constraint has a scale that makes its error relative: the rest volume psi(X0) for the global volume, each
// part's own rest volume for a volume part's (bounded below by what its sum rounds and above by psi(X0):
// hard_constraints.cpp), the bone's rest length for the skeleton's.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/solver/internal/energy/deformation_energy.h"

namespace sd {

class HardConstraints {
 public:
  // Keeps a reference to the energy.
  HardConstraints(const DeformationEnergy& energy, bool volume);

  int count() const { return volume_count_ + skeleton_count_; }
  bool empty() const { return count() == 0; }
  int volume_count() const { return volume_count_; }  // the first entries
  int skeleton_count() const { return skeleton_count_; }
  // The one global volume of a closed mesh and nothing else: restoration can run on psi's cubic.
  bool only_global_volume() const;
  // The constraints that are not linear in X (the volumes, the bones' lengths), in order. The others (a skeleton's
  // held middles) are linear: a step from a point that holds them keeps them exactly, at any alpha.
  std::vector<int> nonlinear() const;

  // g at the point of an evaluation (from its volume and skeleton entries), and at X.
  Eigen::VectorXd values(const EnergyEvaluation& e) const;
  Eigen::VectorXd values(const Vertices& X) const;
  // The gradients in X: #V by 3K.
  Eigen::MatrixXd gradients(const Vertices& X) const;
  // Only the volume's, #V by 3 volume_count() (a subspace maps them with its other W^T pass).
  Eigen::MatrixXd volume_gradients(const Vertices& X) const;
  // Only the skeleton's, at the evaluation's points, in the space whose point rows are `rows` (r by 3
  // skeleton_count(); rows = W^T m_q for the subspace, the m_q themselves for X).
  Eigen::MatrixXd skeleton_gradients(const EnergyEvaluation& e, const Eigen::MatrixXd& rows) const;

  const Eigen::VectorXd& scales() const { return scales_; }
  const DeformationEnergy& energy() const { return *energy_; }

  // The constraints along the line X + R t (R: #V by 3K, one direction per constraint): what restoration's Newton
  // steps evaluate. The skeleton's points move linearly, by their rows^T R (computed once), so each step costs
  // O(#points K) for them and only the volume's are evaluated at X + R t (O(#V K)).
  class Along {
   public:
    // point_motion: the skeleton's points' motion along R (#points by 3K), when the caller has it (else computed
    // here as rows^T R, O(#V #points K)); points: the skeleton's points at X, likewise (else rows^T X).
    Along(const HardConstraints& hard, const Vertices& X, const Eigen::MatrixXd& R,
          const Eigen::MatrixXd& point_motion = Eigen::MatrixXd(), const Eigen::MatrixXd& points = Eigen::MatrixXd());
    Vertices at(const Eigen::VectorXd& t) const;
    // g at X + R t: one pass over the triangles for the volume's (none for the skeleton's). With `point` and a
    // volume constraint, also X + R t (formed for the volume's anyway; left as it was without one).
    Eigen::VectorXd values(const Eigen::VectorXd& t, Vertices* point = nullptr) const;
    // d g_k / d t_l at X + R t (K by the number of directions): the volume's gradients there (a second pass)
    // dotted with R.
    Eigen::MatrixXd slopes(const Eigen::VectorXd& t) const;

   private:
    Eigen::MatrixXd points_at(const Eigen::VectorXd& t) const;  // the skeleton's points at X + R t

    const HardConstraints* hard_;
    const Vertices* X_;
    const Eigen::MatrixXd* R_;
    Eigen::MatrixXd points_;  // the skeleton's points at X
    Eigen::MatrixXd motion_;  // their motion per unit t_l: rows^T R, #points by 3K
  };
  // max_k |g_k| / scale_k (0 for none; infinite where a g_k is not finite); over the constraints `rows` only (g holds
  // every constraint).
  double relative_error(const Eigen::VectorXd& g) const;
  double relative_error(const Eigen::VectorXd& g, const std::vector<int>& rows) const;

 private:
  // |g_k| / scale_k, infinite where g_k is not finite.
  double scaled(const Eigen::VectorXd& g, Eigen::Index k) const;

  const DeformationEnergy* energy_;
  int volume_count_ = 0;
  int skeleton_count_ = 0;
  Eigen::VectorXd scales_;
};

}  // namespace sd
