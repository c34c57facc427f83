#include "core/solver/internal/projected_pcg.h"

#include <cmath>
#include <sstream>

#include "core/error.h"

namespace sd {
namespace {

double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }

}  // namespace

ProjectedPcg::ProjectedPcg(PcgOperator op, const Eigen::MatrixXd& b, const Eigen::MatrixXd& c, double g,
                           Eigen::Index image_rows)
    : op_(std::move(op)), c_(c), constrained_(c.size() > 0) {
  h_ = Eigen::MatrixXd::Zero(b.rows(), b.cols());
  image_ = Eigen::MatrixXd::Zero(image_rows, b.cols());
  r_ = b;
  if (constrained_) {
    Mc_ = op_.precondition(c_);
    cMc_ = dot(c_, Mc_);
    if (!(cMc_ > 0.0) || !std::isfinite(cMc_)) {
      std::ostringstream message;
      message << "volume constraint: c^T N^-1 c = " << cMc_
              << " is not positive (the volume gradient is orthogonal to the space of the step)";
      throw Error(ErrorCode::NumericalFailure, message.str());
    }
    if (g != 0.0) {  // start on the linearized constraint c.h = -g
      const double scale = -g / cMc_;
      Eigen::MatrixXd AMc;
      op_.apply(Mc_, AMc, Mc_image_);
      ++products_;
      h_ = scale * Mc_;
      image_ = scale * Mc_image_;
      r_ += scale * AMc;
      start_image_known_ = true;
    }
  }
  precondition_residual();
  p_ = -z_;
  first_direction_ = p_;
  rz_ = rz0_ = dot(r_, z_);
}

Eigen::MatrixXd ProjectedPcg::project(const Eigen::MatrixXd& r, double* sigma) const {
  Eigen::MatrixXd z = op_.precondition(r);
  if (!constrained_) return z;
  const double s = dot(c_, z) / cMc_;
  z -= s * Mc_;
  if (sigma) *sigma = s;
  return z;
}

void ProjectedPcg::precondition_residual() {
  double sigma = 0.0;
  z_ = project(r_, &sigma);
  // Residual update (Gould, Hribar and Nocedal 2001, section 6): r's component along c only feeds the
  // multiplier; removing it each iteration keeps r small, so rounding does not pull the iterates off the
  // projected problem in long runs (the full space takes 50 iterations per step on real models).
  if (constrained_) {
    r_ -= sigma * c_;
    removed_sigma_ += sigma;
  }
}

double ProjectedPcg::lambda() const {
  if (!constrained_) return 0.0;
  double sigma = 0.0;
  project(r_, &sigma);
  return -(sigma + removed_sigma_);
}

double ProjectedPcg::relative_residual() const {
  if (!(rz0_ > 0.0)) return 0.0;  // the start is already optimal
  return std::sqrt(std::max(rz_, 0.0) / rz0_);
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
