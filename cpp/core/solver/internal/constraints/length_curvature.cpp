#include "core/solver/internal/constraints/length_curvature.h"

#include "core/solver/internal/constraints/skeleton_constraints.h"

namespace sd {

LengthCurvature::LengthCurvature(const HardConstraints& hard, const EnergyEvaluation& e, const Eigen::MatrixXd& rows,
                                 const LastMultipliers& last) {
  const SkeletonConstraints* skeleton = hard.energy().skeleton();
  if (!skeleton || hard.skeleton_count() == 0) return;
  const Eigen::VectorXd& lambda = last.for_skeleton(hard.energy().skeleton_version());
  if (lambda.size() != hard.count() || !lambda.allFinite()) return;
  // The skeleton's constraints follow the volume's, its B lengths first (skeleton_constraints.h).
  for (int b = 0; b < skeleton->bone_count(); ++b) {
    const double multiplier = lambda[hard.volume_count() + b];
    const std::array<int, 2>& joints = skeleton->skeleton().bones[static_cast<size_t>(b)];
    const Eigen::RowVector3d d = e.skeleton_points.row(joints[1]) - e.skeleton_points.row(joints[0]);
    const double length = d.norm();
    if (multiplier == 0.0 || !(length > 0.0)) continue;
    const Eigen::Vector3d u = d.transpose() / length;
    bones_.push_back({rows.col(joints[1]) - rows.col(joints[0]),
                      (multiplier / length) * (Eigen::Matrix3d::Identity() - u * u.transpose())});
  }
}

void LengthCurvature::add_times(const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) const {
  for (const Bone& bone : bones_)
    for (Eigen::Index t = 0; t < V.cols() / 3; ++t) {
      const Eigen::RowVector3d along = bone.r.transpose() * V.middleCols(3 * t, 3);
      AV.middleCols(3 * t, 3).noalias() += bone.r * (along * bone.H);
    }
}

std::function<void(const Eigen::MatrixXd&, Eigen::MatrixXd&)> LengthCurvature::term() const {
  if (empty()) return {};
  return [this](const Eigen::MatrixXd& V, Eigen::MatrixXd& AV) { add_times(V, AV); };
}

}  // namespace sd
