#include "core/solver/internal/constraints/hard_constraints.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "core/solver/internal/constraints/direction_blocks.h"

namespace sd {

namespace {

// Each volume constraint's scale (its error is relative to it): psi(X0) for the one global volume; for a part its
// own rest volume |V_k(X0)|, so that every part keeps its own to the tolerance (relative to the whole, a part a
// thousandth of the model's size could drift by 1e-9 of the whole, 100% of its own), within two bounds:
// - at least kPartRoundingDigits of the sum of its triangles' |cone terms| about the reference point, the size of
//   what the part's sum rounds: a painted patch on a flat face encloses only rounding noise (5e-16 of the whole), and
//   a tolerance below the noise would refuse every trial;
// - at most psi(X0): a cavity wall and the body around it are parts of volumes larger than the material's, and held
//   each to 1e-9 of its own they would hold the material only to 1e-9 (V_o + V_i) / (V_o - V_i).
Eigen::VectorXd volume_scales(const DeformationEnergy& energy) {
  constexpr double kPartRoundingDigits = 1e-4;
  const double whole = std::abs(energy.rest_volume());
  const Eigen::VectorXd& rest = energy.rest_constraint_volumes();
  const std::vector<int>& part = energy.volume_parts();
  if (part.empty()) return Eigen::VectorXd::Constant(1, whole);
  Eigen::VectorXd terms = Eigen::VectorXd::Zero(rest.size());
  const Vertices& X = energy.rest_positions();
  const Faces& F = energy.faces();
  const Eigen::RowVector3d& o = energy.volume_reference();
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = X.row(F(f, 0)) - o, b = X.row(F(f, 1)) - o, c = X.row(F(f, 2)) - o;
    terms[part[static_cast<size_t>(f)]] += std::abs(a.cross(b).dot(c)) / 6.0;
  }
  return rest.cwiseAbs().cwiseMax(kPartRoundingDigits * terms).cwiseMin(whole);
}

}  // namespace

HardConstraints::HardConstraints(const DeformationEnergy& energy, bool volume)
    : energy_(&energy),
      volume_count_(volume ? energy.constraint_count() : 0),
      skeleton_count_(energy.skeleton() ? energy.skeleton()->count() : 0) {
  scales_.resize(count());
  if (volume_count_ > 0) scales_.head(volume_count_) = volume_scales(energy);
  if (skeleton_count_ > 0) scales_.tail(skeleton_count_) = energy.skeleton()->scales();
}

bool HardConstraints::only_global_volume() const {
  return volume_count_ == 1 && skeleton_count_ == 0 && !energy_->has_caps();
}

std::vector<int> HardConstraints::nonlinear() const {
  std::vector<int> out;
  for (int k = 0; k < volume_count_; ++k) out.push_back(k);
  for (int k = 0; k < skeleton_count_; ++k)
    if (!energy_->skeleton()->is_linear(k)) out.push_back(volume_count_ + k);
  return out;
}

Eigen::VectorXd HardConstraints::values(const EnergyEvaluation& e) const {
  Eigen::VectorXd g(count());
  g.head(volume_count_) = e.constraint.head(volume_count_);
  if (skeleton_count_ > 0) g.tail(skeleton_count_) = e.skeleton_constraint;
  return g;
}

Eigen::VectorXd HardConstraints::values(const Vertices& X) const {
  Eigen::VectorXd g(count());
  if (volume_count_ > 0) g.head(volume_count_) = energy_->constraints(X);
  if (skeleton_count_ > 0) g.tail(skeleton_count_) = energy_->skeleton()->values(energy_->skeleton()->points(X));
  return g;
}

Eigen::MatrixXd HardConstraints::volume_gradients(const Vertices& X) const {
  return volume_count_ > 0 ? energy_->constraint_gradients(X) : Eigen::MatrixXd(X.rows(), 0);
}

Eigen::MatrixXd HardConstraints::skeleton_gradients(const EnergyEvaluation& e, const Eigen::MatrixXd& rows) const {
  if (skeleton_count_ == 0) return Eigen::MatrixXd(rows.rows(), 0);
  return energy_->skeleton()->gradients(e.skeleton_points, rows);
}

Eigen::MatrixXd HardConstraints::gradients(const Vertices& X) const {
  Eigen::MatrixXd G(X.rows(), 3 * count());
  G.leftCols(3 * volume_count_) = volume_gradients(X);
  if (skeleton_count_ > 0) {
    const SkeletonConstraints& s = *energy_->skeleton();
    G.rightCols(3 * skeleton_count_) = s.gradients(s.points(X), s.point_rows());
  }
  return G;
}

HardConstraints::Along::Along(const HardConstraints& hard, const Vertices& X, const Eigen::MatrixXd& R,
                              const Eigen::MatrixXd& point_motion, const Eigen::MatrixXd& points)
    : hard_(&hard), X_(&X), R_(&R) {
  if (const SkeletonConstraints* s = hard.skeleton_count() > 0 ? hard.energy_->skeleton() : nullptr) {
    points_ = points.rows() == s->point_rows().cols() ? points : s->points(X);
    motion_ = point_motion.cols() == R.cols() ? point_motion : Eigen::MatrixXd(s->point_rows().transpose() * R);
  }
}

Vertices HardConstraints::Along::at(const Eigen::VectorXd& t) const {
  // One matrix-vector product per axis reads R once (K separate updates would read and write Y K times).
  Vertices Y = *X_;
  for (int axis = 0; axis < 3; ++axis) Y.col(axis).noalias() += axis_columns(*R_, axis) * t;
  return Y;
}

Eigen::MatrixXd HardConstraints::Along::points_at(const Eigen::VectorXd& t) const {
  Eigen::MatrixXd points = points_;
  for (Eigen::Index l = 0; l < t.size(); ++l) points += t[l] * motion_.middleCols(3 * l, 3);
  return points;
}

Eigen::VectorXd HardConstraints::Along::values(const Eigen::VectorXd& t, Vertices* point) const {
  const HardConstraints& h = *hard_;
  Eigen::VectorXd g(h.count());
  if (h.volume_count_ > 0 && !point && t.isZero()) {
    g.head(h.volume_count_) = h.energy_->constraints(*X_);  // X itself: no copy
  } else if (h.volume_count_ > 0) {
    Vertices Y = at(t);
    g.head(h.volume_count_) = h.energy_->constraints(Y);
    if (point) *point = std::move(Y);
  }
  if (h.skeleton_count_ > 0) g.tail(h.skeleton_count_) = h.energy_->skeleton()->values(points_at(t));
  return g;
}

Eigen::MatrixXd HardConstraints::Along::slopes(const Eigen::VectorXd& t) const {
  const HardConstraints& h = *hard_;
  const Eigen::Index K = h.count(), Kv = h.volume_count_;
  Eigen::MatrixXd slope(K, R_->cols() / 3);  // one column per direction
  if (Kv > 0) {
    const Eigen::MatrixXd G = h.energy_->constraint_gradients(t.isZero() ? *X_ : at(t));
    slope.topRows(Kv).setZero();
    for (int axis = 0; axis < 3; ++axis)
      slope.topRows(Kv).noalias() += axis_columns(G, axis).transpose() * axis_columns(*R_, axis);
  }
  if (h.skeleton_count_ > 0) slope.bottomRows(h.skeleton_count_) = h.energy_->skeleton()->slopes(points_at(t), motion_);
  return slope;
}

double HardConstraints::relative_error(const Eigen::VectorXd& g) const {
  double e = 0;
  for (Eigen::Index k = 0; k < g.size(); ++k) e = std::max(e, scaled(g, k));
  return e;
}

double HardConstraints::relative_error(const Eigen::VectorXd& g, const std::vector<int>& rows) const {
  double e = 0;
  for (int k : rows) e = std::max(e, scaled(g, k));
  return e;
}

double HardConstraints::scaled(const Eigen::VectorXd& g, Eigen::Index k) const {
  // std::max drops a NaN: a constraint that is not a number would count as held.
  return std::isfinite(g[k]) ? std::abs(g[k]) / scales_[k] : std::numeric_limits<double>::infinity();
}

}  // namespace sd
