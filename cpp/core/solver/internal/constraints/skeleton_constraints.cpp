#include "core/solver/internal/constraints/skeleton_constraints.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/basis/mean_value_coordinates.h"
#include "core/error.h"

namespace sd {
namespace {

// The samples' layout is skeleton_points()' (skeleton.h). The report measures straightness at all seven; the
// constraints hold the middle one (k = 3) on the segment.
constexpr int kMiddle = 3;

// Column 7b + k: sample k of bone b less (1 - t_k) joint a + t_k joint c, over the points.
Eigen::MatrixXd sample_offsets(const Skeleton& s) {
  const Eigen::Index J = s.joints.rows(), samples = kBoneSamples * static_cast<Eigen::Index>(s.bones.size());
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(J + samples, samples);
  for (size_t b = 0; b < s.bones.size(); ++b)
    for (int k = 0; k < kBoneSamples; ++k) {
      const Eigen::Index column = kBoneSamples * static_cast<Eigen::Index>(b) + k;
      out(J + column, column) = 1.0;
      out(s.bones[b][0], column) -= 1.0 - bone_sample_fraction(k);
      out(s.bones[b][1], column) -= bone_sample_fraction(k);
    }
  return out;
}

// Distance of p from the segment [a, c].
double segment_distance(const Eigen::RowVector3d& p, const Eigen::RowVector3d& a, const Eigen::RowVector3d& c) {
  const Eigen::RowVector3d d = c - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

// Below this the constraints' gradients count as dependent: their Schur complement would be near singular.
constexpr double kIndependent = 1e-8;

// Rows chosen greedily so that the correlation matrix of those kept (their Gram matrix with normalised columns) keeps
// its smallest eigenvalue above kIndependent. That holds exactly when the matrix less kIndependent I has a Cholesky
// factor, and the factor grows a block of rows at a time: a trial costs a triangular solve, not an eigen-
// decomposition of everything kept (which took 14 s for 255 bones in the bar's full space, beside the Gram matrix).
class IndependentRows {
 public:
  explicit IndependentRows(const Eigen::MatrixXd& gram) {
    const Eigen::VectorXd s = gram.diagonal().cwiseMax(1e-300).cwiseSqrt().cwiseInverse();
    correlation_ = s.asDiagonal() * gram * s.asDiagonal();
    factor_ = Eigen::MatrixXd::Zero(gram.rows(), gram.rows());
  }
  // Keeps the rows `trial` (indices into the Gram matrix) when they leave everything kept independent.
  bool add(const std::vector<Eigen::Index>& trial) {
    const Eigen::Index k = static_cast<Eigen::Index>(kept_.size()), t = static_cast<Eigen::Index>(trial.size());
    Eigen::MatrixXd cross(k, t), block(t, t);
    for (Eigen::Index j = 0; j < t; ++j) {
      for (Eigen::Index i = 0; i < k; ++i) cross(i, j) = correlation_(kept_[static_cast<size_t>(i)], trial[j]);
      for (Eigen::Index i = 0; i < t; ++i) block(i, j) = correlation_(trial[i], trial[j]);
    }
    block.diagonal().array() -= kIndependent;
    if (k > 0) {
      factor_.topLeftCorner(k, k).triangularView<Eigen::Lower>().solveInPlace(cross);
      block -= cross.transpose() * cross;
    }
    const Eigen::LLT<Eigen::MatrixXd> schur(block);
    if (schur.info() != Eigen::Success || !schur.matrixLLT().allFinite()) return false;
    factor_.block(k, 0, t, k) = cross.transpose();
    factor_.block(k, k, t, t) = schur.matrixL();
    kept_.insert(kept_.end(), trial.begin(), trial.end());
    return true;
  }

 private:
  Eigen::MatrixXd correlation_, factor_;
  std::vector<Eigen::Index> kept_;
};

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
  Eigen::MatrixXd out(rows.rows(), kBoneSamples * bone_count());
  for (int b = 0; b < bone_count(); ++b) {
    const auto [a, c] = skeleton_.bones[static_cast<size_t>(b)];
    for (int k = 0; k < kBoneSamples; ++k)
      out.col(kBoneSamples * b + k) = rows.col(sample(b, k)) - (1.0 - bone_sample_fraction(k)) * rows.col(a) -
                                      bone_sample_fraction(k) * rows.col(c);
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
    c[a] -= 1.0 - bone_sample_fraction(row.sample);
    c[e] -= bone_sample_fraction(row.sample);
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

std::vector<int> SkeletonConstraints::representable(const Eigen::MatrixXd& rows, bool subspace) const {
  // Every candidate row: the lengths, then each bone's straightness rows. The Gram matrix of all of them at once,
  // entry (c_k^T R c_l) (d_k . d_l) with R = rows^T rows, made as (rows C)^T (rows C): a set's Gram matrix is its
  // block (made pair by pair, the choice below cost O(B^5): 4 s at 44 bones on the bar, over a minute at 255).
  std::vector<Row> candidates;
  for (int b = 0; b < bone_count(); ++b) candidates.push_back({b, 0, -1});
  for (int b = 0; b < bone_count(); ++b)
    for (const Row& row : straightness_rows(b, 1)) candidates.push_back(row);
  const Eigen::Index T = static_cast<Eigen::Index>(candidates.size());
  const Eigen::MatrixXd rest = skeleton_points(skeleton_);
  // C: the rows' coefficients over the points, three at most per column (sparse: the full space's rows are #V long).
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd D(T, 3);
  for (Eigen::Index k = 0; k < T; ++k) {
    const Eigen::VectorXd c = coefficients(candidates[static_cast<size_t>(k)]);
    for (Eigen::Index q = 0; q < c.size(); ++q)
      if (c[q] != 0.0) entries.emplace_back(q, k, c[q]);
    D.row(k) = direction(candidates[static_cast<size_t>(k)], rest);
  }
  Eigen::SparseMatrix<double> C(rows_.cols(), T);
  C.setFromTriplets(entries.begin(), entries.end());
  // (rows C)^T (rows C) by blocks of rows: the full space's rows are #V long, and rows C whole would hold #V x 4B
  // doubles (350 MB for 255 bones on the 43k-vertex bar).
  constexpr Eigen::Index kRowBlock = 4096;
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(T, T);
  for (Eigen::Index r0 = 0; r0 < rows.rows(); r0 += kRowBlock) {
    const Eigen::MatrixXd block = rows.middleRows(r0, std::min(kRowBlock, rows.rows() - r0)) * C;
    gram.noalias() += block.transpose() * block;
  }
  IndependentRows independent(gram.cwiseProduct(D * D.transpose()));
  // The lengths one at a time (the same test as all at once), so that the message can name the first that fails.
  for (int b = 0; b < bone_count(); ++b) {
    if (independent.add({b})) continue;
    const std::string bone = "bone " + std::to_string(b);
    throw Error(ErrorCode::InvalidSkeleton,
                subspace ? "skeleton: " + bone + "'s length cannot be kept independently of the bones before it in " +
                               "this subspace (too few cage vertices or modes around the bones); use fewer bones, a " +
                               "finer cage or more modes, or the full space"
                         : "skeleton: " + bone + "'s length is fixed by the bones before it (bones along each other: " +
                               "joints at the same place or a loop of bones on one line; or many short bones in a " +
                               "row, whose points the mesh's coordinates cannot tell apart); separate them or use " +
                               "fewer, longer bones");
  }
  std::vector<int> out(static_cast<size_t>(bone_count()), 0);
  for (int b = 0; b < bone_count(); ++b) {
    const Eigen::Index middle = bone_count() + 3 * b;  // its three straightness rows
    out[static_cast<size_t>(b)] = independent.add({middle, middle + 1, middle + 2}) ? 1 : 0;
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
    for (int k = 0; k < kBoneSamples; ++k)
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
