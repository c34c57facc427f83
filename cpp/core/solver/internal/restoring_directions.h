// The directions along which restoration (volume_restoration.h, docs/method.md section 8) puts a line-search trial
// back on the hard constraints, and the coefficients it solves for along them.
//
// A step solver gives one direction per constraint (W N^-1 c_k in the subspace), and Newton drives every
// constraint to zero along them. A skeleton's held middles are linear in X: a step from a point that holds them
// keeps them at any alpha, and only the volumes and the bones' lengths drift. For them NonlinearRestoration makes
// one combination per nonlinear constraint, R' = R S^-1 E (S = C^T R, the constraints' slopes along R; E the unit
// columns of the nonlinear ones): each moves its own constraint by one to first order and the linear ones by
// exactly zero, so Newton runs on the nonlinear constraints along a third of the columns (an arm with two bones:
// 3 directions instead of 9), and the images R' are kept while the step's images are.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh/mesh.h"

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
  // The combinations for `step` (made at X, where the skeleton's points are `points`), or null where every
  // constraint is nonlinear or the slopes cannot be inverted (then restore along the step's own directions).
  const RestoringDirections* update(const HardConstraints& hard, const RestoringDirections& step, const Vertices& X,
                                    const Eigen::MatrixXd& points);
  // Whether they serve a trial whose constraint values are g: its linear constraints hold (to rounding). A trial
  // from a point that broke them (a skeleton set on a bent pose, a step cut short there) restores along the step's
  // own directions, which put the linear ones back too.
  bool serves(const HardConstraints& hard, const Eigen::VectorXd& g) const;

 private:
  std::shared_ptr<const Eigen::MatrixXd> source_;  // the step's images they were made from (held: never reused)
  std::vector<int> nonlinear_;                     // of the constraints they were made for
  RestoringDirections combined_;
  bool usable_ = false;
};

}  // namespace sd
