// The bones' lengths' curvature in the Hessian of the Lagrangian (docs/method.md section 5.4, "Curvature").
//
// Why: a step solves A h = -(b + C lambda) on the linearised constraints, with A the energy's Gauss-Newton matrix.
// The constraints' own curvature, sum_k lambda_k Hess g_k, is missing from A. For a bone's length
// g = |q_c - q_a| - L it is lambda / |d| (I - u u^T) on d = q_c - q_a (u = d / |d|): the bone turning bends its
// length's linearisation, and without it Gauss-Newton converged only linearly with a skeleton (the arm: 132
// iterations). A compressed bone has lambda < 0, so the term makes A indefinite; on the constraints' tangent space,
// where the projected PCG of the fast steps works, it stays positive definite near a minimum, and where it does not
// the PCG meets non-positive curvature and the step is solved again without it (pcg_step.h).
//
// The multipliers are the last step's (LastMultipliers: kept by the step solver through a drag, shared by the
// subspace's full and reduced integration, forgotten on a reset or new handles, never used for another skeleton):
// they tend to the solution's, so the step tends to Newton's on the Lagrangian. The term changes only the model of a
// step, not the fixed point (du = 0 where b + C lambda = 0), so the converged pose is the same.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "core/solver/internal/constraints/hard_constraints.h"

namespace sd {

// The last step's multipliers, kept by the step solver for the next step's curvature, with the skeleton they
// belong to (the energy's skeleton version): those of another skeleton are not used, even with as many bones.
class LastMultipliers {
 public:
  void keep(const Eigen::VectorXd& lambda, long skeleton_version) {
    lambda_ = lambda;
    skeleton_version_ = skeleton_version;
  }
  void clear() { lambda_.resize(0); }
  // Empty unless kept for this skeleton version.
  const Eigen::VectorXd& for_skeleton(long skeleton_version) const {
    static const Eigen::VectorXd none;
    return skeleton_version == skeleton_version_ ? lambda_ : none;
  }

 private:
  Eigen::VectorXd lambda_;
  long skeleton_version_ = -1;
};

class LengthCurvature {
 public:
  // hard: the solve's constraints; e: the evaluation at the linearisation (its skeleton points); rows: the points'
  // rows in the step's space (W^T m_q, m by #points; m_q itself in the full space); last: the last step's
  // multipliers (none for this skeleton, or of another size than `hard`: no curvature, as without a skeleton).
  LengthCurvature(const HardConstraints& hard, const EnergyEvaluation& e, const Eigen::MatrixXd& rows,
                  const LastMultipliers& last);
  bool empty() const { return bones_.empty(); }
  // AV += sum over bones of r_b (r_b^T V) H_b per 3-column block of V (rows.rows() by 3s).
  void add_times(const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) const;
  // add_times as PcgStepProblem::curvature takes it: empty when there is no curvature. It refers to this object,
  // which must outlive the step.
  std::function<void(const Eigen::MatrixXd& V, Eigen::MatrixXd& AV)> term() const;

 private:
  struct Bone {
    Eigen::VectorXd r;  // the difference of its end joints' rows
    Eigen::Matrix3d H;  // lambda / |d| (I - u u^T)
  };
  std::vector<Bone> bones_;
};

}  // namespace sd
