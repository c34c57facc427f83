// The deformation energy and its hard constraints (docs/method.md section 5):
//   f(X) = [ S (L X - delta_hat(X)) ; w_pos C^1/2 (Phi X - V_hat) Q ; w_s O^T P^T (X - X0) ],   E(X) = 1/2 |f(X)|^2,
//   g(X) = psi(X) - psi(X0)                                  (the volume constraint),
// or, with volume parts (part_volume.h), K constraints g_k(X) = V_k(X) - V_k(X0), one per part. Unless set
// otherwise the parts are default_volume_parts: one per connected component, and one for a single open
// component (whose holes are capped by fans); a single closed component has the one global psi.
// with L the cotangent Laplacian of the rest mesh (applied to x, y, z alike), S and C the diagonal weights of
// energy_weighting.h (by area, or identities for the uniform weighting), delta_hat the rotation-invariant
// Laplacian coordinates of S L (so S is folded into L and delta_hat: laplacian() is S L, with an open mesh's
// boundary rows adjusted as laplacian_coordinates.h says), Phi the selection of the handle vertices and V_hat
// their targets, Q the projection across each handle vertex's line (handle_line.h; I for a point target), and, with
// a skeleton, its soft straightness term: P^T X its points (skeleton_constraints.h), O^T P^T X their samples' offsets
// from their places on their bones (less the rest offsets, zero but for rounding), w_s the straightness weight
// (docs/method.md section 5.4). Its Jacobian
// J_f = [ S L (x) I3 - J_delta_hat(X) ; w_pos C^1/2 Phi (x) I3 ; w_s (P O)^T (x) I3 ] is never formed as one matrix:
// EnergyJacobian applies it (and J_f^T J_f) to blocks of vectors.
//
// Conventions used by every solver file:
//   - positions are Vertices (#V by 3, row-major, flattened index 3 * vertex + axis);
//   - "blocks" of s vectors in X space are Eigen::MatrixXd of #V by 3s, column-major, vector t in
//     columns 3t .. 3t+2 (x, y, z). This is the shape BasisMatrix::multiply consumes, so one stream
//     over W serves x, y, z and several right-hand sides at once (cost model in docs/benchmarks.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>
#include <memory>
#include <optional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/volume.h"
#include "core/parts/part_volume.h"
#include "core/solver/handle_line.h"
#include "core/solver/internal/energy/energy_weighting.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/solver/internal/constraints/skeleton_constraints.h"

namespace sd {

struct EnergyEvaluation {
  Vertices laplacian_residual;            // L X - delta_hat(X), #V by 3
  Vertices position_residual;             // w_pos C^1/2 (Phi X - V_hat) Q, #handles by 3
  double laplacian_energy = 0;            // 1/2 |S (L X - delta_hat(X))|^2
  double position_energy = 0;             // 1/2 |w_pos C^1/2 (Phi X - V_hat)|^2
  Eigen::MatrixXd straightness_residual;  // w_s O^T P^T (X - X0): 7B by 3 (empty without the term)
  double straightness_energy = 0;         // 1/2 |w_s O^T P^T (X - X0)|^2
  double energy = 0;                      // their sum, 1/2 |f|^2
  double volume = 0;                      // psi(X) (with parts: the sum of the part volumes)
  Eigen::VectorXd constraint;             // g(X): psi(X) - psi(X0), or V_k(X) - V_k(X0) per part
  // With a skeleton (skeleton_constraints.h): its points at X and its constraints' values there (empty without).
  Eigen::MatrixXd skeleton_points;
  Eigen::VectorXd skeleton_constraint;
  bool finite() const;
};

class EnergyJacobian;

class DeformationEnergy {
 public:
  // X0, F: the rest mesh (manifold, consistently oriented, open or closed, enclosing a positive volume once
  // its holes are capped; validated by the caller). Throws sd::Error when the volume is not positive.
  DeformationEnergy(const Vertices& X0, const Faces& F, EnergyWeighting weighting = EnergyWeighting::Area);
  ~DeformationEnergy();

  int vertex_count() const { return static_cast<int>(X0_.rows()); }
  const Vertices& rest_positions() const { return X0_; }
  const Faces& faces() const { return F_; }
  // The Laplacian as the residual applies it: S L (row-scaled by the weighting; L 1 = 0 still holds).
  const Eigen::SparseMatrix<double>& laplacian() const { return L_; }
  // Re-weights the energy (rebuilding S L and the rotation-invariant coordinates: O(#V)); the handles keep
  // their vertices and targets.
  void set_weighting(EnergyWeighting weighting);
  EnergyWeighting weighting() const { return weighting_; }
  const EnergyWeights& weights() const { return weights_; }
  // L_ij per block of the Jacobian rows' pattern (laplacian_coordinates.h).
  const std::vector<double>& laplacian_blocks() const { return coordinates_.laplacian_blocks(); }
  // The rotation-invariant coordinates of S L (their rows also serve sampled vertices: restricted()).
  const LaplacianCoordinates& coordinates() const { return coordinates_; }
  // psi(X0): the sum of the default parts' rest volumes (capped for an open mesh).
  double rest_volume() const { return rest_volume_; }
  // The point every volume, gradient and restoring cubic is summed about (volume.h): the rest mesh's
  // volume_reference, fixed here so that the constraints are the same functions through every solve.
  const VolumeReference& volume_reference() const { return volume_reference_; }
  // Vertices on the boundary of an open mesh (0 when closed).
  int boundary_vertex_count() const { return coordinates_.boundary_count(); }
  double rest_diagonal() const { return rest_diagonal_; }  // of the rest bounding box
  // Changes whenever the handle term does (handles, targets, weights): lets callers keep what they derive from it.
  long handle_terms_version() const { return handle_terms_version_; }

  // Volume parts (one part index per triangle, validated by the caller): K constraints instead of the global
  // one. Empty: the default parts again (default_volume_parts: one per component; none for one closed one).
  void set_volume_parts(const std::vector<int>& part_of_face);
  // True when the constraints are part volumes (set, or the default ones of an open or multi-part mesh).
  bool has_volume_parts() const { return parts_ != nullptr; }
  // True when a constraint includes caps (over holes or between parts): psi's triangle sum alone is not it.
  bool has_caps() const { return parts_ != nullptr && parts_->curve_count() > 0; }
  const std::vector<int>& volume_parts() const;
  int constraint_count() const { return parts_ ? parts_->count() : 1; }
  // Changes with each set_volume_parts: lets callers keep what they derive from the constraints' gradients.
  long volume_parts_version() const { return volume_parts_version_; }
  // psi(X0), or V_k(X0) per part.
  const Eigen::VectorXd& rest_constraint_volumes() const { return rest_constraint_volumes_; }
  int fallback_count() const { return coordinates_.fallback_count(); }

  // The skeleton's constraints (skeleton_constraints.h; nullptr: none), kept beside the volume's by every
  // Gauss-Newton solve (hard_constraints.h). skeleton_version() changes with each set, so that what a step solver
  // derives from the points' rows (W^T m_q) can be kept.
  void set_skeleton(std::unique_ptr<SkeletonConstraints> skeleton);
  const SkeletonConstraints* skeleton() const { return skeleton_.get(); }
  // Which bones keep their midpoints (SkeletonConstraints::keep_straight); a new version.
  void keep_bones_straight(const std::vector<int>& held_per_bone);
  long skeleton_version() const { return skeleton_version_; }
  // The soft straightness term's weight w_s (0: none): each bone's seven samples pulled towards their places on the
  // segment between its joints, each like a point handle of weight w_s. It is part of the handle terms (their
  // version changes), as it is a constant quadratic term of the positions like theirs.
  void set_straightness_weight(double w);
  double straightness_weight() const { return straightness_weight_; }
  bool has_straightness_term() const { return skeleton_ && straightness_weight_ > 0.0; }

  // Handle vertices in target order (unique, in range: checked by the caller), made of groups of the given
  // sizes (empty: one group), which the area weighting weighs as wholes. Targets reset to the rest positions.
  void set_handles(const std::vector<int>& vertices, const std::vector<int>& group_sizes = {});
  const std::vector<int>& handle_vertices() const { return handles_; }
  // #handles by 3.
  void set_targets(const Vertices& targets);
  const Vertices& targets() const { return targets_; }
  void set_position_weight(double w);
  double position_weight() const { return weight_; }
  // The weight of each handle vertex's residual row, w_pos sqrt(c_k) (#handles).
  const Eigen::VectorXd& handle_row_weights() const { return handle_row_weights_; }
  // The handle groups' sizes, in the order of handle_vertices() (one group of all when none were given).
  const std::vector<int>& handle_group_sizes() const { return group_sizes_; }
  // The projection constraint (handle_line.h): one line per handle vertex (empty: every one a point target;
  // set_handles clears them). Each row's unit direction u_k follows its target (an eye's line turns with it).
  void set_handle_lines(const std::vector<HandleLine>& per_vertex);
  bool has_handle_lines() const { return !lines_.empty(); }
  // u_k per handle vertex (#handles by 3; zero rows are point targets); empty without lines.
  const Vertices& line_directions() const { return line_directions_; }
  // (x - t) Q_k for a handle vertex k: the part of its offset across its line (the offset itself without one).
  Eigen::RowVector3d across_line(Eigen::Index k, const Eigen::RowVector3d& offset) const;

  // skeleton_points: the skeleton's points at X where the caller maps them itself (StepSolver::skeleton_points).
  EnergyEvaluation evaluate(const Vertices& X, const std::optional<Eigen::MatrixXd>& skeleton_points = {}) const;
  // e's skeleton entries at X (nothing without a skeleton): O(#V #points), unless `points` gives the points.
  void evaluate_skeleton(const Vertices& X, EnergyEvaluation& e,
                         const std::optional<Eigen::MatrixXd>& points = {}) const;
  // Recomputes the handle terms of an evaluation at X, and the straightness term from its skeleton points (after the
  // targets or a weight changed; the Laplacian terms and the volume depend on X alone): O(#handles) instead of O(#V).
  void update_position_terms(const Vertices& X, EnergyEvaluation& e) const;
  // J_f at X (the factored Laplacian rows L (x) I3 - J_delta_hat, laplacian_rows.h; O(#V)).
  EnergyJacobian jacobian(const Vertices& X) const;
  // J = J_f at X, reusing J's storage (the solver's per-iteration path).
  void update_jacobian(const Vertices& X, EnergyJacobian& J) const;
  // Gradient of the volume, #V by 3 (docs/method.md section 5).
  Vertices volume_gradient(const Vertices& X) const;
  // g(X) (K entries) and the sum of the volumes, without the rest of an evaluation.
  Eigen::VectorXd constraints(const Vertices& X, double* volume = nullptr) const;
  // The gradients of g's entries: #V by 3K (volume_gradient when K = 1 without parts).
  Eigen::MatrixXd constraint_gradients(const Vertices& X) const;

  // The constant part of J_f^T J_f for one coordinate: K = (S L)^T (S L) + w_pos^2 Phi^T C Phi (#V by #V). It is
  // the preconditioner of the fast full-space step and, projected, N = W^T K W of the subspace step.
  Eigen::SparseMatrix<double> constant_normal_matrix() const;

 private:
  // The weighted Laplacian and the coordinates fitted to it, for the current weighting.
  void build_laplacian_terms();
  // handle_row_weights_ from the weighting, the groups and the position weight.
  void update_handle_weights();
  // line_directions_ from the lines and the targets.
  void update_line_directions();

  Vertices X0_;
  Faces F_;
  EnergyWeighting weighting_;
  EnergyWeights weights_;
  Eigen::SparseMatrix<double> cotan_;  // L, unweighted
  Eigen::SparseMatrix<double> L_;      // S L
  LaplacianCoordinates coordinates_;
  VertexTriangles around_;  // for the volume gradient
  VolumeReference volume_reference_;
  double rest_volume_ = 0;
  std::vector<int> default_parts_;  // default_volume_parts of the rest mesh
  double rest_diagonal_ = 0;
  long handle_terms_version_ = 0;
  std::unique_ptr<PartVolumes> parts_;
  Eigen::VectorXd rest_constraint_volumes_;
  std::vector<int> handles_;
  std::vector<int> group_sizes_;
  Vertices targets_;
  double weight_ = 1.0;
  Eigen::VectorXd handle_row_weights_;
  std::vector<HandleLine> lines_;
  Vertices line_directions_;
  std::unique_ptr<SkeletonConstraints> skeleton_;
  long skeleton_version_ = 0;
  double straightness_weight_ = 0.0;
  long volume_parts_version_ = 0;
};

// J_f at one point; cheap to apply to blocks (each product is O(#V) per vector). Its Laplacian rows
// M = L (x) I3 - J_delta_hat are held in factored form (laplacian_rows.h); the handle rows are implicit.
class EnergyJacobian {
 public:
  explicit EnergyJacobian(const DeformationEnergy& energy);

  // J_f^T f for the residual of an evaluation at the same point: #V by 3 (the X-space gradient of E).
  Eigen::MatrixXd gradient(const EnergyEvaluation& e) const;
  // Which terms normal_product applies: all, or all but the straightness term, for a caller that applies that one in
  // its own space (the subspace: m by 7B rows instead of #V by 7B).
  enum class Terms { All, WithoutStraightness };
  // J_f^T J_f applied to a block (#V by 3s) -> #V by 3s.
  Eigen::MatrixXd normal_product(const Eigen::MatrixXd& block, Terms terms = Terms::All) const;
  // The Laplacian rows of J_f, M = S L (x) I3 - J_delta_hat, applied to X-space vectors (#V by 3s), and M^T.
  Eigen::MatrixXd laplacian_rows(const Eigen::MatrixXd& v) const;
  Eigen::MatrixXd laplacian_rows_transpose(const Eigen::MatrixXd& v) const { return M_.multiply_transpose(v); }

  // M = L (x) I3 - d delta_hat / d X, 3#V by 3#V, interleaved (index 3 * vertex + axis): exact modes.
  Eigen::SparseMatrix<double> laplacian_rows_matrix() const { return M_.to_sparse(); }
  const DeformationEnergy& energy() const { return *energy_; }

 private:
  friend class DeformationEnergy;  // update_jacobian rewrites M_ in place
  const DeformationEnergy* energy_;
  LaplacianRows M_;
};

// Layout helpers: a #V by 3s block <-> 3#V by s interleaved columns.
Eigen::MatrixXd interleave(const Eigen::MatrixXd& block);
Eigen::MatrixXd deinterleave(const Eigen::MatrixXd& columns);
// Frobenius inner product of two equally shaped blocks (the dot product of the flattened vectors).
inline double block_dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }
// Largest vertex displacement: max over rows of the row norm of a #V by 3 block.
double max_row_norm(const Eigen::MatrixXd& d);

}  // namespace sd
