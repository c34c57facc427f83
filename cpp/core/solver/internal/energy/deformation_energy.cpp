#include "core/solver/internal/energy/deformation_energy.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/mesh/cotan_laplacian.h"
#include "core/error.h"
#include "core/mesh/volume.h"

namespace sd {

bool EnergyEvaluation::finite() const {
  return std::isfinite(energy) && std::isfinite(volume) && constraint.allFinite() && laplacian_residual.allFinite() &&
         position_residual.allFinite() && skeleton_points.allFinite() && skeleton_constraint.allFinite();
}

namespace {

// diag(s) L: each row i scaled by s_i (the weighting's Laplacian rows; rows still sum to zero).
Eigen::SparseMatrix<double> scale_rows(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& s) {
  return s.asDiagonal() * L;
}

}  // namespace

DeformationEnergy::DeformationEnergy(const Vertices& X0, const Faces& F, EnergyWeighting weighting)
    : X0_(X0),
      F_(F),
      weighting_(weighting),
      weights_(X0, F),
      cotan_(cotan_laplacian(X0, F)),
      L_(scale_rows(cotan_, weights_.laplacian_row_scales(weighting))),
      coordinates_(X0, F, L_),
      around_(vertex_triangles(static_cast<int>(X0.rows()), F)),
      volume_reference_(sd::volume_reference(X0, F)),
      default_parts_(default_volume_parts(X0, F)),
      rest_diagonal_(bounding_box_diagonal(X0)),
      targets_(0, 3) {
  // An open mesh's boundary rows differ from L (laplacian_coordinates.h): the energy runs on the adjusted ones.
  if (coordinates_.boundary_count() > 0) L_ = coordinates_.laplacian();
  set_volume_parts({});
  rest_volume_ = rest_constraint_volumes_.sum();
  if (!(rest_volume_ > 0.0))
    throw Error(ErrorCode::InvalidMesh,
                "deformation: the rest mesh encloses volume " + std::to_string(rest_volume_) +
                    " (with its holes capped; it must enclose a positive volume, outward oriented)");
}

void DeformationEnergy::set_weighting(EnergyWeighting weighting) {
  if (weighting == weighting_) return;
  weighting_ = weighting;
  L_ = scale_rows(cotan_, weights_.laplacian_row_scales(weighting));
  coordinates_ = LaplacianCoordinates(X0_, F_, L_);
  if (coordinates_.boundary_count() > 0) L_ = coordinates_.laplacian();  // as in the constructor
  update_handle_weights();
}

void DeformationEnergy::set_position_weight(double w) {
  weight_ = w;
  update_handle_weights();
}

void DeformationEnergy::set_straightness_weight(double w) {
  straightness_weight_ = w;
  ++handle_terms_version_;
  if (has_straightness_term()) skeleton_->offset_rows();  // made here, not inside a solve's products
}

void DeformationEnergy::update_handle_weights() {
  ++handle_terms_version_;
  handle_row_weights_ = weight_ * weights_.handle_coefficients(weighting_, handles_, group_sizes_).array().sqrt();
}

void DeformationEnergy::set_volume_parts(const std::vector<int>& part_of_face) {
  const std::vector<int>& parts = part_of_face.empty() ? default_parts_ : part_of_face;
  ++volume_parts_version_;
  if (parts.empty()) {  // one closed component: the one global volume
    parts_.reset();
    rest_constraint_volumes_ = Eigen::VectorXd::Constant(1, signed_volume(X0_, F_, volume_reference_));
    return;
  }
  auto next = std::make_unique<PartVolumes>(F_, vertex_count(), parts);
  rest_constraint_volumes_ = next->evaluate(X0_, volume_reference_);
  parts_ = std::move(next);
}

const std::vector<int>& DeformationEnergy::volume_parts() const {
  static const std::vector<int> none;
  return parts_ ? parts_->part_of_face() : none;
}

Eigen::VectorXd DeformationEnergy::constraints(const Vertices& X, double* volume) const {
  if (!parts_) {
    const double psi = signed_volume(X, F_, volume_reference_);
    if (volume) *volume = psi;
    return Eigen::VectorXd::Constant(1, psi - rest_constraint_volumes_[0]);
  }
  const Eigen::VectorXd v = parts_->evaluate(X, volume_reference_);
  if (volume) *volume = v.sum();
  return v - rest_constraint_volumes_;
}

Eigen::MatrixXd DeformationEnergy::constraint_gradients(const Vertices& X) const {
  return parts_ ? parts_->gradients(X, volume_reference_) : Eigen::MatrixXd(volume_gradient(X));
}

DeformationEnergy::~DeformationEnergy() = default;

void DeformationEnergy::set_handles(const std::vector<int>& vertices, const std::vector<int>& group_sizes) {
  const std::vector<int> one_group{static_cast<int>(vertices.size())};
  const std::vector<int>& sizes = group_sizes.empty() ? one_group : group_sizes;
  weights_.handle_coefficients(weighting_, vertices, sizes);  // throws on sizes that do not match, before any change
  handles_ = vertices;
  group_sizes_ = sizes;
  update_handle_weights();
  targets_.resize(static_cast<Eigen::Index>(handles_.size()), 3);
  for (size_t k = 0; k < handles_.size(); ++k) targets_.row(static_cast<Eigen::Index>(k)) = X0_.row(handles_[k]);
  lines_.clear();
  update_line_directions();
  ++handle_terms_version_;
}

void DeformationEnergy::set_handle_lines(const std::vector<HandleLine>& per_vertex) {
  if (!per_vertex.empty() && per_vertex.size() != handles_.size())
    throw Error("handle lines: " + std::to_string(per_vertex.size()) + " lines for " + std::to_string(handles_.size()) +
                " handle vertices");
  for (const HandleLine& line : per_vertex) validate_handle_line(line, "handle lines");
  const bool any = std::any_of(per_vertex.begin(), per_vertex.end(),
                               [](const HandleLine& l) { return l.kind != HandleLine::Kind::None; });
  lines_ = any ? per_vertex : std::vector<HandleLine>();
  update_line_directions();
  ++handle_terms_version_;
}

void DeformationEnergy::update_line_directions() {
  if (lines_.empty()) {
    line_directions_.resize(0, 3);
    return;
  }
  line_directions_.resize(static_cast<Eigen::Index>(lines_.size()), 3);
  for (size_t k = 0; k < lines_.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    line_directions_.row(row) = line_direction(lines_[k], targets_.row(row));
  }
}

Eigen::RowVector3d DeformationEnergy::across_line(Eigen::Index k, const Eigen::RowVector3d& offset) const {
  if (lines_.empty()) return offset;
  const Eigen::RowVector3d u = line_directions_.row(k);
  return offset - offset.dot(u) * u;
}

void DeformationEnergy::set_targets(const Vertices& targets) {
  if (targets.rows() != static_cast<Eigen::Index>(handles_.size()))
    throw Error("targets: " + std::to_string(targets.rows()) + " rows for " + std::to_string(handles_.size()) +
                " handle vertices");
  targets_ = targets;
  update_line_directions();  // an eye's lines pass through the new targets
  ++handle_terms_version_;
}

EnergyEvaluation DeformationEnergy::evaluate(const Vertices& X,
                                             const std::optional<Eigen::MatrixXd>& skeleton_points) const {
  EnergyEvaluation e;
  e.laplacian_residual = coordinates_.laplacian_residual(X);
  e.laplacian_energy = 0.5 * e.laplacian_residual.squaredNorm();
  e.constraint = constraints(X, &e.volume);
  evaluate_skeleton(X, e, skeleton_points);
  update_position_terms(X, e);
  return e;
}

void DeformationEnergy::evaluate_skeleton(const Vertices& X, EnergyEvaluation& e,
                                          const std::optional<Eigen::MatrixXd>& points) const {
  if (!skeleton_) return;
  e.skeleton_points = points ? *points : skeleton_->points(X);
  e.skeleton_constraint = skeleton_->values(e.skeleton_points);
}

void DeformationEnergy::set_skeleton(std::unique_ptr<SkeletonConstraints> skeleton) {
  skeleton_ = std::move(skeleton);
  ++skeleton_version_;
  ++handle_terms_version_;  // the straightness term comes or goes with it
  if (has_straightness_term()) skeleton_->offset_rows();
}

void DeformationEnergy::keep_bones_straight(const std::vector<int>& held_per_bone) {
  if (!skeleton_) return;
  skeleton_->keep_straight(held_per_bone);
  ++skeleton_version_;
}

void DeformationEnergy::update_position_terms(const Vertices& X, EnergyEvaluation& e) const {
  e.position_residual.resize(static_cast<Eigen::Index>(handles_.size()), 3);
  for (size_t k = 0; k < handles_.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    e.position_residual.row(row) = handle_row_weights_[row] * across_line(row, X.row(handles_[k]) - targets_.row(row));
  }
  e.position_energy = 0.5 * e.position_residual.squaredNorm();
  // The straightness term from the evaluation's points (O(#points #samples)), so that a new weight is taken too.
  e.straightness_residual.resize(0, 3);
  if (has_straightness_term() && e.skeleton_points.rows() == skeleton_->offset_combinations().rows())
    e.straightness_residual = straightness_weight_ * skeleton_->offsets(e.skeleton_points);
  e.straightness_energy = 0.5 * e.straightness_residual.squaredNorm();
  e.energy = e.laplacian_energy + e.position_energy + e.straightness_energy;
}

EnergyJacobian DeformationEnergy::jacobian(const Vertices& X) const {
  EnergyJacobian J(*this);
  update_jacobian(X, J);
  return J;
}

void DeformationEnergy::update_jacobian(const Vertices& X, EnergyJacobian& J) const {
  if (J.energy_ != this) J = EnergyJacobian(*this);
  J.M_.linearize(coordinates_, X);  // M = L (x) I3 - J_delta_hat
}

Vertices DeformationEnergy::volume_gradient(const Vertices& X) const {
  return sd::volume_gradient(X, F_, around_, volume_reference_);
}

// With handle lines this keeps a point target's w^2 per handle vertex: an upper bound of the exact w^2 Q, and a
// constant-per-axis matrix, which is what the preconditioners that use it need.
Eigen::SparseMatrix<double> DeformationEnergy::constant_normal_matrix() const {
  Eigen::SparseMatrix<double> K = L_.transpose() * L_;
  for (size_t k = 0; k < handles_.size(); ++k)  // the diagonal is already in the pattern
    K.coeffRef(handles_[k], handles_[k]) +=
        handle_row_weights_[static_cast<Eigen::Index>(k)] * handle_row_weights_[static_cast<Eigen::Index>(k)];
  K.makeCompressed();
  return K;
}

EnergyJacobian::EnergyJacobian(const DeformationEnergy& energy) : energy_(&energy), M_(&energy.laplacian_blocks()) {}

Eigen::MatrixXd EnergyJacobian::gradient(const EnergyEvaluation& e) const {
  // J_f^T f = M^T r_lap + Phi^T (w C^1/2) Q r_pos, and Q r_pos = r_pos (r_pos is already across the line).
  Eigen::MatrixXd g = M_.multiply_transpose(Eigen::MatrixXd(e.laplacian_residual));
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  const auto& handles = energy_->handle_vertices();
  for (size_t k = 0; k < handles.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    g.row(handles[k]) += w[row] * e.position_residual.row(row);
  }
  // + w_s (P O) r_s for the straightness term (an evaluation made before the weight or the skeleton changed has none).
  if (energy_->has_straightness_term() &&
      e.straightness_residual.rows() == energy_->skeleton()->offset_combinations().cols())
    g.noalias() += energy_->straightness_weight() * energy_->skeleton()->offset_rows() * e.straightness_residual;
  return g;
}

Eigen::MatrixXd EnergyJacobian::laplacian_rows(const Eigen::MatrixXd& v) const { return M_.multiply(v); }

Eigen::MatrixXd EnergyJacobian::normal_product(const Eigen::MatrixXd& block, Terms terms) const {
  Eigen::MatrixXd out = M_.multiply_transpose(M_.multiply(block));
  const Eigen::VectorXd& w = energy_->handle_row_weights();
  const auto& handles = energy_->handle_vertices();
  for (size_t k = 0; k < handles.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    const double w2 = w[row] * w[row];
    for (Eigen::Index t = 0; t < block.cols() / 3; ++t)
      out.block(handles[k], 3 * t, 1, 3) += w2 * energy_->across_line(row, block.block(handles[k], 3 * t, 1, 3));
  }
  if (terms == Terms::All && energy_->has_straightness_term()) {  // + w_s^2 (P O) (P O)^T, on x, y and z alike
    const Eigen::MatrixXd& R = energy_->skeleton()->offset_rows();
    const double ws = energy_->straightness_weight();
    out.noalias() += R * (ws * ws * (R.transpose() * block));
  }
  return out;
}

Eigen::MatrixXd interleave(const Eigen::MatrixXd& block) {
  const Eigen::Index n = block.rows(), s = block.cols() / 3;
  Eigen::MatrixXd out(3 * n, s);
  for (Eigen::Index t = 0; t < s; ++t)
    for (int a = 0; a < 3; ++a)
      for (Eigen::Index i = 0; i < n; ++i) out(3 * i + a, t) = block(i, 3 * t + a);
  return out;
}

Eigen::MatrixXd deinterleave(const Eigen::MatrixXd& columns) {
  const Eigen::Index n = columns.rows() / 3, s = columns.cols();
  Eigen::MatrixXd out(n, 3 * s);
  for (Eigen::Index t = 0; t < s; ++t)
    for (int a = 0; a < 3; ++a)
      for (Eigen::Index i = 0; i < n; ++i) out(i, 3 * t + a) = columns(3 * i + a, t);
  return out;
}

double max_row_norm(const Eigen::MatrixXd& d) { return d.rows() == 0 ? 0.0 : d.rowwise().norm().maxCoeff(); }

}  // namespace sd
