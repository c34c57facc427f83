#include "core/solver/internal/steps/projected_pcg.h"

#include <climits>
#include <cmath>
#include <sstream>

#include "core/error.h"
#include "core/solver/internal/steps/constrained_step.h"

namespace sd {
namespace {

double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }

}  // namespace

ProjectedPcg::ProjectedPcg(PcgOperator op, const Eigen::MatrixXd& b, const Eigen::MatrixXd& C, const Eigen::VectorXd& g,
                           Eigen::Index image_rows)
    : op_(std::move(op)), c_(C), constrained_(C.size() > 0) {
  h_ = Eigen::MatrixXd::Zero(b.rows(), b.cols());
  image_ = Eigen::MatrixXd::Zero(image_rows, b.cols());
  r_ = b;
  const Eigen::Index K = c_.cols() / 3;
  removed_sigma_ = Eigen::VectorXd::Zero(K);
  if (constrained_) {
    Mc_ = op_.precondition(c_);  // every constraint's m x 3 block in one call
    G_ = block_products(c_, Mc_);
    if (!(g.array() == 0.0).all()) {  // start on the linearized constraints C^T h = -g
      const Eigen::VectorXd scale = solve_schur(G_, -g, "N");
      Mc_image_.resize(image_rows, 3 * K);
      for (Eigen::Index k = 0; k < K; ++k) {
        Eigen::MatrixXd AMc, image;
        op_.apply(Mc_.middleCols(3 * k, 3), AMc, image);
        ++products_;
        Mc_image_.middleCols(3 * k, 3) = image;
        h_ += scale[k] * Mc_.middleCols(3 * k, 3);
        image_ += scale[k] * image;
        r_ += scale[k] * AMc;
      }
      start_image_known_ = true;
    } else if (K > 0) {
      solve_schur(G_, Eigen::VectorXd::Zero(K), "N");  // G must be positive definite either way
    }
  }
  precondition_residual();
  p_ = -z_;
  first_direction_ = p_;
  rz_ = rz0_ = dot(r_, z_);
}

Eigen::MatrixXd ProjectedPcg::project(const Eigen::MatrixXd& r, Eigen::VectorXd* sigma) const {
  Eigen::MatrixXd z = op_.precondition(r);
  if (!constrained_) return z;
  const Eigen::VectorXd s = solve_schur(G_, block_products(c_, z).col(0), "N");
  for (Eigen::Index k = 0; k < s.size(); ++k) z -= s[k] * Mc_.middleCols(3 * k, 3);
  if (sigma) *sigma = s;
  return z;
}

void ProjectedPcg::precondition_residual() {
  Eigen::VectorXd sigma;
  z_ = project(r_, &sigma);
  // Residual update (Gould, Hribar and Nocedal 2001, section 6): r's components along C only feed the
  // multipliers; removing them each iteration keeps r small, so rounding does not pull the iterates off the
  // projected problem in long runs (the full space takes 50 iterations per step on real models).
  if (constrained_) {
    for (Eigen::Index k = 0; k < sigma.size(); ++k) r_ -= sigma[k] * c_.middleCols(3 * k, 3);
    removed_sigma_ += sigma;
  }
}

Eigen::VectorXd ProjectedPcg::lambda() const {
  if (!constrained_) return Eigen::VectorXd();
  Eigen::VectorXd sigma;
  project(r_, &sigma);
  return -(sigma + removed_sigma_);
}

double ProjectedPcg::relative_residual() const {
  if (!(rz0_ > 0.0)) return 0.0;  // the start is already optimal
  return std::sqrt(std::max(rz_, 0.0) / rz0_);
}

void ProjectedPcg::run_further(double tolerance, int more_products) {
  run(tolerance, more_products > INT_MAX - products_ ? INT_MAX : products_ + more_products);
}

void ProjectedPcg::run(double tolerance, int max_products) {
  while (!broken_ && products_ < max_products && relative_residual() > tolerance) iterate();
}

void ProjectedPcg::iterate() {
  Eigen::MatrixXd Ap, pImage;
  op_.apply(p_, Ap, pImage);
  ++products_;
  if (!first_image_known_) {
    first_image_ = pImage;
    first_image_known_ = true;
  }
  const double pAp = dot(p_, Ap);
  if (!(pAp > 0.0) || !std::isfinite(pAp)) {
    broken_ = true;  // A is singular along p (or numerics failed): keep the iterate reached so far
    return;
  }
  const double alpha = rz_ / pAp;
  h_ += alpha * p_;
  image_ += alpha * pImage;
  r_ += alpha * Ap;
  precondition_residual();
  const double rz_new = dot(r_, z_);
  p_ = -z_ + (rz_new / rz_) * p_;
  rz_ = rz_new;
}

}  // namespace sd
