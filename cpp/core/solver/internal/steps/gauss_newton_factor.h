// The fast steps' factor preconditioner (docs/method.md section 11.1): a Cholesky factor of
// P = N (x) I3 + R, N's constant part plus the rotation terms R (the stiffest vertices' exactly, the others' through
// rotation clusters: factor_rotation_terms.h) at a recent point, kept across iterations and the frames of a drag
// while it serves.
//
// Why: N = W^T (L^T L + handles) W leaves out d delta_hat / dX, so it prices the local rotations of the surface as
// if the Laplacian coordinates could not turn with it. Where a few vertices carry most of the Gauss-Newton
// matrix (slivers on the hand bones), PCG preconditioned by N spends up to its cap of 50 products per iteration;
// P leaves it about 2. Where they are spread (the boy, the cow), the clusters hold them.
//
// When to (re)make it: a factor costs as much as some number of PCG products (`cost`, estimated by the caller from
// the sizes, so the choice does not depend on timing or threads). The products it could have saved, those beyond
// kGoodProducts in each PCG run since the last factor, are added up, and a factor is made when they reach its cost
// (the rent-or-buy rule: never more than twice what the better of "always N" and "factor at once" would have
// spent). A model on which N does well (a capsule in a bar cage: about 3 products) never pays for one; a factor
// that stops serving (the pose moved on) is remade the same way. A factor whose debt reaches its cost again within
// kServingRuns runs did not pay for itself: the rotation terms miss what makes this model's PCG long. It is
// dropped, and none is made again until clear(). The factor is kept in float32 and solved in double
// (packed_factor.h).
//
// Long runs buy sooner. PCG runs that average kLongRunExcess products or more beyond kGoodProducts say that N misses
// much of the Gauss-Newton matrix (the boy: 21 and 33 products; the hand bones: about 30; the cow: 16): such runs
// go on, so the first factor is bought at half its cost (at worst 3 times the better choice instead of 2). The
// boy's converged full solve took 3150 -> 2340 ms natively, the cow's 331 -> 292, the hand bones' 979 -> 915; the
// capsule (about 3 products per run) never qualifies. Only full-integration runs count as long: a reduced
// integration's products' costs are estimates (twice too high on the hand bones) beside a fixed cost per iteration,
// and there the factor bought at half price made the hand bones' solve slower (575 -> 990 ms). The app drags with
// reduced integration and settles with full: the settle's first long run qualifies, and the debt its drag left counts.
//
// A run stops where the factor falls due: the debt is counted after each PCG run, so a full-integration run may spend
// only the products left before the debt reaches the price that holds before it (products_before); the next run buys
// the factor. A settle on the boy spent 41 products in one run where 12 made the factor due.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "core/solver/internal/steps/packed_factor.h"

namespace sd {

// llt^-1 R for a block R (m by 3s) of s vectors of 3m unknowns (index axis * m + j), the factor being 3m x 3m.
Eigen::MatrixXd solve_stacked(const Eigen::LLT<Eigen::MatrixXd>& llt, const Eigen::MatrixXd& R);

class GaussNewtonFactor {
 public:
  // Cage or spectral subspaces of at most this many unknowns per axis get the factor; larger ones keep N (a dense
  // 3m x 3m factor costs m^3 and 9 m^2 doubles).
  static constexpr int kMaxUnknownsPerAxis = 600;
  // Products per PCG run that a good preconditioner still needs.
  static constexpr int kGoodProducts = 2;
  static constexpr int kServingRuns = 2;
  // Full-integration PCG runs that averaged at least this many products beyond kGoodProducts buy the first factor
  // at half its cost (see the header's comment).
  static constexpr double kLongRunExcess = 5.0;

  // The products a factor would have saved since the last one (or since clear()).
  double debt() const { return debt_; }
  // Whether a factor costing `cost` products should be made before the next PCG run (false again until clear()
  // once a factor did not serve).
  bool due(double cost);
  // The debt at which a factor costing `cost` products is due.
  double price(double cost) const;
  // The most products over W the next PCG run may spend (beyond its start on the constraints) before the debt
  // reaches `price`, at least kGoodProducts + 1 (a huge number when no factor can be due): a run stops there, so that
  // the rent paid never runs past the price by a whole run's length (the next run buys the factor).
  int products_before(double price) const;
  // Factors P (3m x 3m, index axis * m + j). Returns false (and holds no factor) when P is not positive definite;
  // then no factor is due again until clear() (the caller keeps N).
  bool factor(const Eigen::MatrixXd& P);
  bool ready() const { return ready_; }
  // P^-1 R for a block R (m by 3s: each m by 3 block is one vector of the 3m unknowns).
  Eigen::MatrixXd solve(const Eigen::MatrixXd& R) const;
  // After each PCG run (with this factor or without one): its products, each costing `weight` products over W (the
  // unit of the factor's cost; a reduced integration's products cost less). Only full integration's runs can be
  // long runs (see above), whatever their weight.
  void record(int products, double weight = 1.0, bool full_integration = true);
  // Drops the factor and the debt (a reset, a new handle set: the solve repeats exactly).
  void clear();

 private:
  PackedFactor factor_;  // P's Cholesky factor, in float32 (packed_factor.h)
  bool ready_ = false;
  bool failed_ = false;  // not positive definite, or it did not serve
  int runs_ = 0;         // PCG runs since the factor was made
  double debt_ = 0;
  // Since the last factor (or clear()), full integration's runs and their products beyond kGoodProducts.
  int full_runs_ = 0;
  double full_excess_ = 0;
};

}  // namespace sd
