// Projected preconditioned conjugate gradients for the equality-constrained quadratic program of one
// Gauss-Newton step with the volume multiplier (constrained_step.h):
//
//   minimize 1/2 h.A h + b.h   subject to   c.h = -g,        A = (J_f W)^T (J_f W) (or J_f^T J_f).
//
// Gould, Hribar and Nocedal (2001): start on the constraint, h0 = s M^-1 c with s = -g / (c.M^-1 c), and
// run PCG with the preconditioner projected onto c.z = 0 in the M metric,
//   proj(r) = M^-1 r - sigma M^-1 c,   sigma = (c.M^-1 r) / (c.M^-1 c),
// so that every iterate stays on the constraint. Unlike solving A u = b and A v = c and combining them,
// each product is applied to one m by 3 block, not two: half the columns per pass over W.
// At the end the multiplier is the least-squares fit of the KKT residual A h + b = -lambda c in the M^-1
// metric: lambda = -sigma(r), with the multiples of c removed from r along the way (the residual update)
// added back. Without a constraint (c empty) this is plain PCG from h = 0.
//
// Blocks are m by 3 (x, y, z of the unknowns); image is W times a block (#V by 3; the identity in the
// full space), accumulated so the caller gets W h without another pass.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace sd {

struct PcgOperator {
  // AP = A P and image = W P for a block P (m by 3).
  std::function<void(const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image)> apply;
  // M^-1 R for a block R (m by 3): the preconditioner.
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& R)> precondition;
};

class ProjectedPcg {
 public:
  // c may be empty (no constraint; g ignored). g = 0 starts at h = 0 without a product. image_rows: rows of
  // an image (#V for W, m for the identity).
  ProjectedPcg(PcgOperator op, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, double g, Eigen::Index image_rows);

  // Iterates until the projected preconditioned residual sqrt(r.z) has dropped by `tolerance` relative to
  // the start, or `max_products` products have been spent in all. May be called again with a tighter
  // tolerance to continue.
  void run(double tolerance, int max_products);

  const Eigen::MatrixXd& h() const { return h_; }
  const Eigen::MatrixXd& image() const { return image_; }  // W h
  double lambda() const;                                   // multiplier of c (0 without a constraint)
  // M^-1 c (the constraint's direction in the M metric) and, when known, its image W M^-1 c.
  const Eigen::MatrixXd& constraint_direction() const { return Mc_; }
  bool constraint_image_known() const { return start_image_known_; }
  const Eigen::MatrixXd& constraint_image() const { return Mc_image_; }
  // The first search direction -proj(b + A h0) (a descent direction of the QP on the constraint) and its
  // image, known once a product has been spent on it.
  const Eigen::MatrixXd& first_direction() const { return first_direction_; }
  bool first_image_known() const { return first_image_known_; }
  const Eigen::MatrixXd& first_image() const { return first_image_; }
  int products() const { return products_; }
  double relative_residual() const;

 private:
  Eigen::MatrixXd project(const Eigen::MatrixXd& r, double* sigma) const;
  void precondition_residual();  // z = proj(r), then the residual update
  void iterate();

  PcgOperator op_;
  Eigen::MatrixXd c_, Mc_, Mc_image_;
  double cMc_ = 0;
  bool constrained_ = false, start_image_known_ = false, first_image_known_ = false, broken_ = false;
  Eigen::MatrixXd h_, image_, r_, z_, p_, first_direction_, first_image_;
  double rz_ = 0, rz0_ = 0;
  double removed_sigma_ = 0;  // sum of the multiples of c taken out of r (the multiplier's share so far)
  int products_ = 0;
};

}  // namespace sd
