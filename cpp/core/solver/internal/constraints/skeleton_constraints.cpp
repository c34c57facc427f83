#include "core/solver/internal/constraints/skeleton_constraints.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "core/basis/mean_value_coordinates.h"
#include "core/error.h"

namespace sd {
namespace {

// Sample k of a bone at fraction (k + 1) / 8 from its first joint. The report measures straightness at all seven;
// the constraints hold the middle one (k = 3) on the segment.
constexpr int kSamples = SkeletonConstraints::kSamplesPerBone;
double fraction(int k) { return (k + 1) / 8.0; }
constexpr int kMiddle = 3;

// The points: the joints, then seven samples per bone.
Vertices skeleton_points(const Skeleton& s) {
  const Eigen::Index J = s.joints.rows();
  Vertices points(J + kSamples * static_cast<Eigen::Index>(s.bones.size()), 3);
  points.topRows(J) = s.joints;
  for (size_t b = 0; b < s.bones.size(); ++b)
    for (int k = 0; k < kSamples; ++k)
      points.row(J + kSamples * static_cast<Eigen::Index>(b) + k) =
          (1.0 - fraction(k)) * s.joints.row(s.bones[b][0]) + fraction(k) * s.joints.row(s.bones[b][1]);
  return points;
}

// Column 7b + k: sample k of bone b less (1 - t_k) joint a + t_k joint c, over the points.
Eigen::MatrixXd sample_offsets(const Skeleton& s) {
  const Eigen::Index J = s.joints.rows(), samples = kSamples * static_cast<Eigen::Index>(s.bones.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(J + samples, samples);
  for (size_t b = 0; b < s.bones.size(); ++b)
    for (int k = 0; k < kSamples; ++k) {
      const Eigen::Index column = kSamples * static_cast<Eigen::Index>(b) + k;
      out(J + column, column) = 1.0;
      out(s.bones[b][0], column) -= 1.0 - fraction(k);
      out(s.bones[b][1], column) -= fraction(k);
    }
  return out;
}

// Distance of p from the segment [a, c].
double segment_distance(const Eigen::RowVector3d& p, const Eigen::RowVector3d& a, const Eigen::RowVector3d& c) {
  const Eigen::RowVector3d d = c - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Smallest eigenvalue of the correlation matrix of a Gram matrix (columns normalised): 0 for dependent ones.
double independence(const Eigen::MatrixXd& gram) {
  const Eigen::VectorXd s = gram.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd correlation = s.asDiagonal() * gram * s.asDiagonal();
  return Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(correlation, Eigen::EigenvaluesOnly).eigenvalues()[0];
}

// Below this the constraints' gradients count as dependent: their Schur complement would be near singular.
constexpr double kIndependent = 1e-8;

}  // namespace

SkeletonConstraints::SkeletonConstraints(const Skeleton& skeleton, const Mesh& mesh) : skeleton_(skeleton) {
  rows_ = mean_value_coordinates(skeleton_points(skeleton), mesh).to_dense().transpose();
  rest_lengths_.resize(bone_count());
  for (int b = 0; b < bone_count(); ++b)
    rest_lengths_[b] = (skeleton.joints.row(skeleton.bones[b][1]) - skeleton.joints.row(skeleton.bones[b][0])).norm();
  held_.assign(static_cast<size_t>(bone_count()), 1);
  rebuild_rows();
  offset_combinations_ = sample_offsets(skeleton);
  rest_offsets_ = offset_combinations_.transpose() * points(mesh.V);
}

const Eigen::MatrixXd& SkeletonConstraints::rows_in(const BasisMatrix& W) const {
  if (W.rows() != rows_.rows())
    throw Error("skeleton: the basis has " + std::to_string(W.rows()) + " rows for a mesh of " +
                std::to_string(rows_.rows()) + " vertices");
  if (rows_basis_ != &W || basis_rows_.rows() != W.cols()) {
    W.multiply_transpose(rows_, basis_rows_);
    basis_offset_rows_ = times_offset_combinations(basis_rows_);
    rows_basis_ = &W;
  }
  return basis_rows_;
}

const Eigen::MatrixXd& SkeletonConstraints::offset_rows() const {
  if (offset_rows_.cols() == 0 && bone_count() > 0) offset_rows_ = times_offset_combinations(rows_);
  return offset_rows_;
}

Eigen::MatrixXd SkeletonConstraints::times_offset_combinations(const Eigen::MatrixXd& rows) const {
  Eigen::MatrixXd out(rows.rows(), kSamples * bone_count());
  for (int b = 0; b < bone_count(); ++b) {
    const auto [a, c] = skeleton_.bones[static_cast<size_t>(b)];
    for (int k = 0; k < kSamples; ++k)
      out.col(kSamples * b + k) =
          rows.col(sample(b, k)) - (1.0 - fraction(k)) * rows.col(a) - fraction(k) * rows.col(c);
  }
  return out;
}

const Eigen::MatrixXd& SkeletonConstraints::offset_rows_in(const BasisMatrix& W) const {
  rows_in(W);
  return basis_offset_rows_;
}

Eigen::MatrixXd SkeletonConstraints::points(const Vertices& X) const { return rows_.transpose() * X; }

Eigen::MatrixXd SkeletonConstraints::offsets(const Eigen::MatrixXd& points) const {
  return offset_combinations_.transpose() * points - rest_offsets_;
}

void SkeletonConstraints::keep_straight(const std::vector<int>& held_per_bone) {
  if (held_per_bone.size() != held_.size()) throw Error("skeleton: one count of held samples per bone");
  for (int h : held_per_bone)
    if (h != 0 && h != 1) throw Error("skeleton: a bone holds its middle sample (1) or none (0)");
  held_ = held_per_bone;
  rebuild_rows();
}

std::vector<SkeletonConstraints::Row> SkeletonConstraints::straightness_rows(int bone, int held) {
  std::vector<Row> rows;
  for (int axis = 0; held == 1 && axis < 3; ++axis) rows.push_back({bone, kMiddle, axis});
  return rows;
}

void SkeletonConstraints::rebuild_rows() {
  constraints_.clear();
  for (int b = 0; b < bone_count(); ++b) constraints_.push_back({b, 0, -1});
  for (int b = 0; b < bone_count(); ++b)
    for (const Row& row : straightness_rows(b, held_[static_cast<size_t>(b)])) constraints_.push_back(row);
  scales_.resize(count());
  for (int k = 0; k < count(); ++k) scales_[k] = rest_lengths_[constraints_[static_cast<size_t>(k)].bone];
}

int SkeletonConstraints::count() const { return static_cast<int>(constraints_.size()); }

Eigen::VectorXd SkeletonConstraints::coefficients(const Row& row) const {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(rows_.cols());
  const auto [a, e] = skeleton_.bones[static_cast<size_t>(row.bone)];
  if (row.axis < 0) {
    c[e] = 1.0;
    c[a] = -1.0;
  } else {  // the sample less its place on the segment
    c[sample(row.bone, row.sample)] = 1.0;
    c[a] -= 1.0 - fraction(row.sample);
    c[e] -= fraction(row.sample);
  }
  return c;
}

Eigen::RowVector3d SkeletonConstraints::direction(const Row& row, const Eigen::MatrixXd& points) const {
  if (row.axis >= 0) return Eigen::RowVector3d::Unit(row.axis);
  const auto [a, e] = skeleton_.bones[static_cast<size_t>(row.bone)];
  const Eigen::RowVector3d d = points.row(e) - points.row(a);
  const double length = d.norm();
  return length > 0.0 ? Eigen::RowVector3d(d / length) : Eigen::RowVector3d::Zero();
}

Eigen::VectorXd SkeletonConstraints::values(const Eigen::MatrixXd& points) const {
  Eigen::VectorXd g(count());
  for (int k = 0; k < count(); ++k) {
    const Row& row = constraints_[static_cast<size_t>(k)];
    const Eigen::RowVector3d v = coefficients(row).transpose() * points;
    g[k] = row.axis < 0 ? v.norm() - rest_lengths_[row.bone] : v[row.axis];
  }
  return g;
}

Eigen::MatrixXd SkeletonConstraints::gradients(const Eigen::MatrixXd& points, const Eigen::MatrixXd& rows) const {
  Eigen::MatrixXd G(rows.rows(), 3 * count());
  for (int k = 0; k < count(); ++k) {
    const Row& row = constraints_[static_cast<size_t>(k)];
    G.middleCols(3 * k, 3).noalias() = (rows * coefficients(row)) * direction(row, points);
  }
  return G;
}

Eigen::MatrixXd SkeletonConstraints::slopes(const Eigen::MatrixXd& points, const Eigen::MatrixXd& motion) const {
  const Eigen::Index L = motion.cols() / 3;
  Eigen::MatrixXd out(count(), L);
  for (int k = 0; k < count(); ++k) {
    const Row& row = constraints_[static_cast<size_t>(k)];
    const Eigen::RowVectorXd moved = coefficients(row).transpose() * motion;  // 1 by 3L
    const Eigen::RowVector3d d = direction(row, points);
    for (Eigen::Index l = 0; l < L; ++l) out(k, l) = moved.segment(3 * l, 3).dot(d);
  }
  return out;
}

std::vector<int> SkeletonConstraints::representable(const Eigen::MatrixXd& rows) const {
  const Eigen::MatrixXd R = rows.transpose() * rows;  // point-by-point inner products of the rows
  const Eigen::MatrixXd rest = skeleton_points(skeleton_);
  // Gram entry of two constraints: (c_k^T R c_l) (d_k . d_l).
  std::vector<Row> kept;
  auto gram_with = [&](const std::vector<Row>& set) {
    Eigen::MatrixXd G(static_cast<Eigen::Index>(set.size()), static_cast<Eigen::Index>(set.size()));
    for (size_t k = 0; k < set.size(); ++k)
      for (size_t l = 0; l < set.size(); ++l)
        G(k, l) =
            coefficients(set[k]).dot(R * coefficients(set[l])) * direction(set[k], rest).dot(direction(set[l], rest));
    return G;
  };
  for (int b = 0; b < bone_count(); ++b) kept.push_back({b, 0, -1});
  if (!(independence(gram_with(kept)) > kIndependent))
    throw Error(ErrorCode::InvalidSkeleton,
                "skeleton: the bones' lengths cannot be kept independently in this subspace (too few cage vertices "
                "or modes around the bones); use fewer bones or a finer cage");
  std::vector<int> out(static_cast<size_t>(bone_count()), 0);
  for (int b = 0; b < bone_count(); ++b) {
    std::vector<Row> trial = kept;
    for (const Row& row : straightness_rows(b, 1)) trial.push_back(row);
    if (!(independence(gram_with(trial)) > kIndependent)) continue;
    kept = std::move(trial);
    out[static_cast<size_t>(b)] = 1;
  }
  return out;
}

SkeletonReport SkeletonConstraints::report(const Eigen::MatrixXd& points, const Eigen::VectorXd& lambda) const {
  SkeletonReport out;
  const Eigen::Index J = skeleton_.joints.rows();
  out.joints = points.topRows(J);
  for (int b = 0; b < bone_count(); ++b) {
    const auto [a, e] = skeleton_.bones[static_cast<size_t>(b)];
    BoneReport r;
    const double L = rest_lengths_[b];
    r.length = (points.row(e) - points.row(a)).norm();
    r.length_error = (r.length - L) / L;
    for (int k = 0; k < kSamples; ++k)
      r.straightness_error =
          std::max(r.straightness_error, segment_distance(points.row(sample(b, k)), points.row(a), points.row(e)) / L);
    r.lambda = lambda.size() > b ? lambda[b] : 0.0;
    r.held_samples = held_[static_cast<size_t>(b)];
    r.straight_hard = r.held_samples == 1;
    out.bones.push_back(r);
  }
  return out;
}

}  // namespace sd
