// Projected preconditioned conjugate gradients for the equality-constrained quadratic program of one
// Gauss-Newton step with the volume multipliers (constrained_step.h):
//
//   minimize 1/2 h.A h + b.h   subject to   C^T h = -g,      A = (J_f W)^T (J_f W) (or J_f^T J_f),
//
// C = [c_1 .. c_K] (K = 1: the volume; K > 1: one per volume part). Gould, Hribar and Nocedal (2001): start on
// the constraints, h0 = M^-1 C s with s = -G^-1 g, G = C^T M^-1 C (K by K), and run PCG with the preconditioner
// projected onto C^T z = 0 in the M metric,
//   proj(r) = M^-1 r - M^-1 C sigma,   sigma = G^-1 (C^T M^-1 r),
// so that every iterate stays on the constraints. Unlike solving A u = b and A V = C and combining them,
// each product is applied to one m by 3 block, not 1 + K: fewer columns per pass over W.
// At the end the multipliers are the least-squares fit of the KKT residual A h + b = -C lambda in the M^-1
// metric: lambda = -sigma(r), with the multiples of C removed from r along the way (the residual update)
// added back. Without constraints (C empty) this is plain PCG from h = 0. With K = 1 every formula is the
// scalar one (sigma = c.M^-1 r / c.M^-1 c), to the bit.
//
// Blocks are m by 3 (x, y, z of the unknowns); image is W times a block (#V by 3; the identity in the
// full space), accumulated so the caller gets W h without another pass.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <utility>

namespace sd {

struct PcgOperator {
  // AP = A P and image = W P for a block P (m by 3).
  std::function<void(const Eigen::MatrixXd& P, Eigen::MatrixXd& AP, Eigen::MatrixXd& image)> apply;
  // M^-1 R for blocks R (m by 3 each, side by side): the preconditioner.
  std::function<Eigen::MatrixXd(const Eigen::MatrixXd& R)> precondition;
};

class ProjectedPcg {
 public:
  // C (m by 3K) may be empty (no constraint; g ignored). g = 0 starts at h = 0 without a product (else the
  // start costs K products). image_rows: rows of an image (#V for W, m for the identity).
  ProjectedPcg(PcgOperator op, const Eigen::MatrixXd& b, const Eigen::MatrixXd& C, const Eigen::VectorXd& g,
               Eigen::Index image_rows);
  // One constraint (or none, with c empty).
  ProjectedPcg(PcgOperator op, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, double g, Eigen::Index image_rows)
      : ProjectedPcg(std::move(op), b, c, Eigen::VectorXd::Constant(1, g), image_rows) {}

  // Iterates until the projected preconditioned residual sqrt(r.z) has dropped by `tolerance` relative to
  // the start, or `max_products` products have been spent in all. May be called again with a tighter
  // tolerance to continue.
  void run(double tolerance, int max_products);
  // run() with up to `more_products` products beyond those spent (at most INT_MAX in all: cgMaxIterations may be
  // INT_MAX, and the sum must not overflow).
  void run_further(double tolerance, int more_products);

  const Eigen::MatrixXd& h() const { return h_; }
  const Eigen::MatrixXd& image() const { return image_; }  // W h
  Eigen::VectorXd lambda() const;                          // multipliers of C (empty without constraints)
  // M^-1 C (the constraints' directions in the M metric, m by 3K) and, when known, their images W M^-1 C.
  const Eigen::MatrixXd& constraint_direction() const { return Mc_; }
  bool constraint_image_known() const { return start_image_known_; }
  const Eigen::MatrixXd& constraint_image() const { return Mc_image_; }
  // The first search direction -proj(b + A h0) (a descent direction of the QP on the constraint) and its
  // image, known once a product has been spent on it.
  const Eigen::MatrixXd& first_direction() const { return first_direction_; }
  bool first_image_known() const { return first_image_known_; }
  // Whether a direction of non-positive curvature (or a non-finite one) stopped the run.
  bool broken() const { return broken_; }
  const Eigen::MatrixXd& first_image() const { return first_image_; }
  int products() const { return products_; }
  double relative_residual() const;

 private:
  Eigen::MatrixXd project(const Eigen::MatrixXd& r, Eigen::VectorXd* sigma) const;
  void precondition_residual();  // z = proj(r), then the residual update
  void iterate();

  PcgOperator op_;
  Eigen::MatrixXd c_, Mc_, Mc_image_;
  Eigen::MatrixXd G_;  // C^T M^-1 C
  bool constrained_ = false, start_image_known_ = false, first_image_known_ = false, broken_ = false;
  Eigen::MatrixXd h_, image_, r_, z_, p_, first_direction_, first_image_;
  double rz_ = 0, rz0_ = 0;
  Eigen::VectorXd removed_sigma_;  // sums of the multiples of C taken out of r (the multipliers' share so far)
  int products_ = 0;
};

}  // namespace sd
