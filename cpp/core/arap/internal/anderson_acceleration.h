// Anderson acceleration of a fixed-point iteration x <- G(x) (type II, as in Walker and Ni 2011; used for
// local-global geometry solvers by Peng et al. 2018, "Anderson acceleration for geometry optimization and
// physics simulation"). From the last `depth` evaluations it extrapolates
//   x_next = g_k - dG theta,   theta = argmin |f_k - dF theta|,   f = G(x) - x,
// where dF, dG hold the differences of consecutive residuals and images. The caller decides whether to
// keep the extrapolated point (ARAP keeps it only when its energy is lower, arap.cpp) and resets the
// history when the map changes (new targets, new handles) or an extrapolation was rejected.
#pragma once

#include <Eigen/Core>
#include <deque>

namespace sd {

class AndersonAcceleration {
 public:
  explicit AndersonAcceleration(int depth = 5) : depth_(depth) {}

  int depth() const { return depth_; }
  void set_depth(int depth);
  void reset();
  // x: where G was evaluated; g = G(x). Returns the next point (g itself until there is history).
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& g);

 private:
  int depth_;
  bool has_last_ = false;
  Eigen::VectorXd last_f_, last_g_;
  std::deque<Eigen::VectorXd> dF_, dG_;
};

}  // namespace sd
