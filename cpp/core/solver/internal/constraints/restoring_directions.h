// The directions along which restoration (volume_restoration.h, docs/method.md section 8) puts a line-search trial
// back on the hard constraints, and the coefficients it solves for along them.
//
// A step solver gives one direction per constraint (W N^-1 c_k in the subspace), and Newton drives every
// constraint to zero along them. A skeleton's held middles are linear in X: a step from a point that holds them
// keeps them at any alpha, and only the volumes and the bones' lengths drift. For them NonlinearRestoration makes
// one combination per nonlinear constraint, R' = R S^-1 E (S = C^T R, the constraints' slopes along R; E the unit
// columns of the nonlinear ones): each moves its own constraint by one to first order and the linear ones by
// exactly zero, so Newton runs on the nonlinear constraints along a third of the columns (an arm with two bones:
// 3 directions instead of 9), and the images R' are kept while the step's images are. They are made only for
// directions a step solver keeps across iterations (the subspace's, through the frames of a drag): making them
// costs a pass over the triangles and a read of R, which directions new at every iteration (the full space's) would
// not repay.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/solver/internal/energy/deformation_energy.h"

namespace sd {

class HardConstraints;

struct RestoringDirections {
  // One m by 3 block per direction (#V by 3 in the full space): the unknowns' motion, and the images in X, shared
  // rather than copied (a subspace step keeps them across the frames of a drag: 9 MB on 43k vertices with K = 9).
  Eigen::MatrixXd du;
  std::shared_ptr<const Eigen::MatrixXd> dx;
  // With a skeleton: its points' motion along each direction (#points by 3 per direction), so restoration need
  // not map the images again; empty: computed from dx.
  Eigen::MatrixXd point_motion;
  // The constraints Newton drives to zero, one per direction, in order; empty: every constraint.
  std::vector<int> driven;

  bool empty() const { return !dx || dx->size() == 0; }
};

// The restoring directions of the nonlinear constraints alone, remade when the step's directions change.
class NonlinearRestoration {
 public:
  // Once per iteration, with its step's directions: notes whether the step solver kept them from the last one.
  void next_step(const RestoringDirections& step);
  // The combinations for a trial whose constraint values are g, made on first use at X (the iteration's point,
  // where the skeleton's points are `points`). Null, so that the trial restores along the step's own directions,
  // where: every constraint is nonlinear; a linear one does not hold at the trial (a skeleton set on a bent pose:
  // the step's directions put it back too); the directions are new this iteration; or the slopes are singular.
  const RestoringDirections* for_trial(const HardConstraints& hard, const RestoringDirections& step, const Vertices& X,
                                       const Eigen::MatrixXd& points, const Eigen::VectorXd& g);

 private:
  const RestoringDirections* make(const HardConstraints& hard, const RestoringDirections& step, const Vertices& X,
                                  const Eigen::MatrixXd& points, std::vector<int> nonlinear);

  std::shared_ptr<const Eigen::MatrixXd> last_step_;  // the directions of the last iteration's step
  bool kept_ = false;                                 // this iteration's are the same

  // What they were made from: the step's images (held, so the address is never reused), the constraints (the
  // energy and its skeleton's version: a new skeleton has other linear constraints, even with images kept) and
  // which of them are nonlinear.
  std::shared_ptr<const Eigen::MatrixXd> source_;
  const DeformationEnergy* energy_ = nullptr;
  long skeleton_version_ = -1;
  std::vector<int> nonlinear_;
  RestoringDirections combined_;
  bool usable_ = false;
};

}  // namespace sd
