#include "core/solver/internal/constraints/volume_restoration.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "core/mesh/volume.h"

namespace sd {
namespace {

// The global volume: scalar Newton on the cubic psi(X + t r).
double restore_global(const DeformationEnergy& energy, Vertices& X, Eigen::MatrixXd& U,
                      const Eigen::MatrixXd& restore_dx, const Eigen::MatrixXd& restore_du, int max_newton) {
  const double psi0 = energy.rest_volume();
  // psi(X + t r) is a cubic in t: its coefficients cost one pass over the triangles, and Newton from t = 0
  // (one or two steps for the small corrections a line-search step leaves) then runs on four numbers.
  const std::array<double, 4> k = volume_along(X, restore_dx, energy.faces(), energy.volume_reference());
  const auto phi_at = [&](double t) { return k[0] - psi0 + t * (k[1] + t * (k[2] + t * k[3])); };
  const auto slope_at = [&](double t) { return k[1] + t * (2.0 * k[2] + 3.0 * t * k[3]); };
  double t = 0.0;
  double phi = phi_at(0.0);
  for (int step = 0; step < max_newton && std::abs(phi) > 1e-15 * psi0; ++step) {
    const double dphi = slope_at(t);
    if (!(std::abs(dphi) > 0.0) || !std::isfinite(dphi)) break;
    const double t_next = t - phi / dphi;
    const double phi_next = phi_at(t_next);
    if (!std::isfinite(phi_next) || std::abs(phi_next) >= std::abs(phi)) break;
    t = t_next;
    phi = phi_next;
  }
  if (t != 0.0) {
    const Vertices moved = X + t * restore_dx;
    if (!moved.allFinite()) return (k[0] - psi0) / psi0;
    X = moved;
    U += t * restore_du;
  }
  return phi / psi0;
}

// The rows `driven` of g, or of a slope matrix, each relative to its constraint's scale (the rest volume, a bone's
// length): Newton's system in the units the tolerance uses. Unscaled, the volume's rows outgrow a bone's by the
// model's size squared, and the LU's invertibility test (relative to the largest pivot) refused the slopes of
// long chains of short bones, so no trial could be restored.
Eigen::MatrixXd driven_rows(const Eigen::MatrixXd& all, const std::vector<int>& driven, const Eigen::VectorXd& scales) {
  Eigen::MatrixXd out(static_cast<Eigen::Index>(driven.size()), all.cols());
  for (size_t k = 0; k < driven.size(); ++k)
    out.row(static_cast<Eigen::Index>(k)) = all.row(driven[k]) / scales[driven[k]];
  return out;
}

// Newton's correction -slope^-1 g of the coefficients. Where the slope's LU calls it singular, the least-squares
// correction of minimum norm, with the slope's columns (one per restoring direction) scaled to a largest entry of 1
// first. Two cases need it (an attack found both): a direction's length is arbitrary, and N^-1 c_k is as small as
// its constraint's gradient, so a closed part a thousandth of the model's size beside the body gave a column 1e-17 of
// the others' and the LU's test (relative to the largest pivot) failed; and a part the subspace cannot reshape (a
// tiny part that the spectral basis's low modes only translate) has a zero row, its volume held by the subspace
// itself. Either way no trial could be restored and the solve stalled at rest. The trial's restored values are
// checked afterwards, so a constraint that truly cannot be restored still fails the trial.
class SlopeSolver {
 public:
  explicit SlopeSolver(const Eigen::MatrixXd& slope) : lu_(slope) {
    if (!slope.allFinite()) return;
    plain_ = lu_.isInvertible();
    if (plain_) {
      ok_ = true;  // as before: the same bits wherever the LU serves
      return;
    }
    column_ = slope.cwiseAbs().colwise().maxCoeff();
    for (Eigen::Index l = 0; l < column_.size(); ++l)
      if (!(column_[l] > 0.0)) column_[l] = 1.0;
    cod_.compute(slope * column_.cwiseInverse().asDiagonal());
    ok_ = cod_.rank() > 0;
  }
  bool ok() const { return ok_; }
  Eigen::VectorXd correction(const Eigen::VectorXd& g) const {
    if (plain_) return -lu_.solve(g);
    return -(cod_.solve(g).array() / column_.transpose().array()).matrix();
  }

 private:
  Eigen::FullPivLU<Eigen::MatrixXd> lu_;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod_;
  Eigen::RowVectorXd column_;
  bool plain_ = false, ok_ = false;
};

// Any other set (volume parts, a skeleton): Newton on g_D(X + R t) = 0 for the coefficients t, one per direction,
// g_D the driven constraints (as many as directions; restoring_directions.h). The slope is kept across steps while
// they gain a thousandfold (chord steps: the corrections a line-search step leaves are small, and the slope at
// their start serves), and refreshed where a step gains less or fails, unless the residual is already rounding:
// each refresh costs a pass over the triangles for the volume's gradients, each value one.
double restore_set(const HardConstraints& hard, Vertices& X, Eigen::MatrixXd& U, const RestoringDirections& r,
                   int max_newton, const Eigen::MatrixXd& points, const Eigen::VectorXd& values) {
  constexpr double kRounding = 1e-13;  // relative errors below this are the sums' rounding, not the direction's
  const Eigen::Index K = r.dx->cols() / 3;
  std::vector<int> driven = r.driven;
  if (driven.empty())
    for (int k = 0; k < hard.count(); ++k) driven.push_back(k);
  const HardConstraints::Along along(hard, X, *r.dx, r.point_motion, points);
  Eigen::VectorXd t = Eigen::VectorXd::Zero(K);
  Eigen::VectorXd g = values.size() == hard.count() ? values : along.values(t);
  double residual = hard.relative_error(g, driven);
  Eigen::MatrixXd slope = driven_rows(along.slopes(t), driven, hard.scales());  // d g_k / d t_l = grad g_k . r_l
  bool slope_at_t = true;
  Vertices Y, Y_next;  // X + R t, X + R t_next (with a volume constraint; else formed once at the end)
  for (int step = 0; step < max_newton && residual > 1e-15; ++step) {
    const SlopeSolver solver(slope);
    if (!solver.ok()) break;
    const Eigen::VectorXd t_next = t + solver.correction(driven_rows(g, driven, hard.scales()));
    const Eigen::VectorXd g_next = along.values(t_next, &Y_next);
    const double residual_next = hard.relative_error(g_next, driven);
    const bool better = std::isfinite(residual_next) && residual_next < residual;
    if (!better && (slope_at_t || residual < kRounding)) break;
    if (better) {
      const bool fast = residual_next <= 1e-3 * residual || residual_next < kRounding;
      t = t_next;
      g = g_next;
      residual = residual_next;
      std::swap(Y, Y_next);
      slope_at_t = false;
      if (fast) continue;
    }
    slope = driven_rows(along.slopes(t), driven, hard.scales());
    slope_at_t = true;
  }
  if ((t.array() != 0.0).any()) {
    if (Y.rows() != X.rows()) Y = along.at(t);
    if (!Y.allFinite()) return hard.relative_error(hard.values(X));
    X = std::move(Y);
    for (Eigen::Index k = 0; k < K; ++k) U += t[k] * r.du.middleCols(3 * k, 3);
  }
  return hard.relative_error(g);
}

}  // namespace

double restore_constraints(const HardConstraints& hard, const DeformationEnergy& energy, Vertices& X,
                           Eigen::MatrixXd& U, const RestoringDirections& directions, int max_newton,
                           const Eigen::MatrixXd& points, const Eigen::VectorXd& values) {
  // The cubic is that of psi, the sum over the triangles: one constraint without caps (not an open mesh's).
  if (hard.only_global_volume()) return restore_global(energy, X, U, *directions.dx, directions.du, max_newton);
  return restore_set(hard, X, U, directions, max_newton, points, values);
}

}  // namespace sd
