// The fast steps' preconditioner on real cages (docs/method.md section 11.1): a Cholesky factor of the whole
// subspace Gauss-Newton matrix A (3m x 3m: the rotation-invariant term's Jacobian and the x-y-z coupling included)
// at a reference point, made from the Laplacian term summed over samples (reduced_subspace.h), and kept across
// iterations and the frames of a drag while it serves.
//
// Why: N = W^T (L^T L + handles) W leaves out d delta_hat / dX, so it prices every local rotation of the surface
// as if the Laplacian coordinates could not turn; A lets them turn. A cage that can bend a model in many places
// (a hand, a figure) has as many such soft directions, and PCG preconditioned by N spends a product on each:
// 10-50 per Gauss-Newton iteration on the real models, against 3 on a capsule in a bar cage. A's own factor at a
// nearby point leaves PCG a few products.
//
// The factor is made (and remade) only when the last PCG run needed more than kRefreshProducts products: a model
// on which N does well (a capsule in a bar cage: about 3) never pays for it. If a fresh factor did not bring a run
// under that, the threshold doubles (the pose changes too fast for the factor to pay), so a poor factor is not
// remade every iteration.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace sd {

class GaussNewtonFactor {
 public:
  // Cage or spectral subspaces of at most this many unknowns per axis get the factor; larger ones keep N (a dense
  // 3m x 3m factor costs m^3 and 9 m^2 doubles).
  static constexpr int kMaxUnknownsPerAxis = 600;
  static constexpr int kRefreshProducts = 6;

  // Whether the next PCG run should have a new factor.
  bool stale() const { return !failed_ && last_products_ > threshold_; }
  // Factors A (3m x 3m, index axis * m + j). Returns false (and holds no factor) when A is not positive definite;
  // then the factor is not stale again until clear() (the caller keeps N).
  bool factor(const Eigen::MatrixXd& A);
  bool ready() const { return ready_; }
  // A_ref^-1 R for a block R (m by 3s: each m by 3 block is one vector of the 3m unknowns).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& R) const;
  // After each PCG run (with this factor or without one): its products.
  void record(int products);
  // Drops the factor and the back-off (a reset, a new handle set: the solve repeats exactly).
  void clear();
  int refreshes() const { return refreshes_; }

 private:
  Eigen::LLT<Eigen::MatrixXd> llt_;
  bool ready_ = false;
  bool fresh_ = false;
  bool failed_ = false;
  int threshold_ = kRefreshProducts;
  int last_products_ = 0;
  int refreshes_ = 0;
};

}  // namespace sd
