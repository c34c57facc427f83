// The Laplacian term with one rotation per cluster of vertices (docs/method.md section 17.1), a reduced
// integration that holds on real cages. The term sums 1/2 |a_i - delta_hat_i(X)|^2 over the vertices, with
// a_i = (S L X)_i. With X = Xbar + W U (Xbar = X0 - W U0) two of its three parts need no vertices: sum |a_i|^2 is
// the quadratic U^T B U + 2 U . b0 + c0 (B = (S L W)^T (S L W), the subspace step's), and |delta_hat_i| is the
// constant |delta_i| (delta = delta_hat(X0), the rest coordinates). Only the cross term needs an approximation:
// delta_hat_i ~ R_c delta_i, the rest coordinate turned by its cluster's rotation. The term becomes
//   E(U) = 1/2 sum_c sum_{i in c} |a_i - R_c(U) delta_i|^2
//        = 1/2 (U . B U + 2 U . b0 + c0 + sum |delta_i|^2) - sum_c tr(R_c M_c),   M_c = D_c U + e_c,
// with D_c = sum_{i in c} delta_i (S L W)_i (3 x m) and e_c made once: an evaluation costs O(#clusters m), no
// vertex. Clusters: farthest-point samples of the rest mesh, each vertex with its nearest along the surface. R_c turns
// with the sample's one-ring: the proper rotation that best maps its rest edges onto its edges at U (Kabsch), from the
// covariance A_c = sum_j (x0_j - x0_s)(x_j - x_s)^T = a_c + Z_c U, linear in U (Z_c made once). Its derivative
// dR_c = [w_c] R_c solves (tr(S_c) I - S_c) w_c = vee(dA^T R_c^T - R_c dA) with S_c = R_c A_c (symmetric), so
// the least squares' Jacobian, gradient and Gauss-Newton matrix J^T J are exact for this E (finite-difference
// tested) and cost O(#clusters m) per product. The rest pose is a fixed point (R_c = I, a_i = delta_i).
// What the rule misses, the cross term's gradient error, is measured on held-out poses (cluster_test_error).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/reduced/reduced_laplacian_term.h"

namespace sd {

// The proper rotation R maximising tr(R A) (Kabsch: R p ~ q for A = sum p q^T).
Eigen::Matrix3d best_rotation(const Eigen::Matrix3d& A);

// Clusters of vertices: their samples, and each vertex's cluster (an index into samples).
struct VertexClusters {
  std::vector<int> samples;
  std::vector<int> owner;
};
// k farthest-point samples of X0 (the first is vertex 0), each vertex with its nearest sample in space.
VertexClusters farthest_point_clusters(const Vertices& X0, int k);
// The same samples, each vertex with the nearest along the mesh's edges (rings: its one-rings), so that a cluster
// never spans two parts that only lie close in space (two components, two fingers); a component that no sample
// reaches gets one of its own (its first vertex). At least k clusters (fewer only on a mesh of fewer vertices).
VertexClusters surface_clusters(const Vertices& X0, const LaplacianCoordinates& rings, int k);

class RotationClusters : public ReducedLaplacianTerm {
 public:
  // B: (S L W)^T (S L W) for the energy's current weighting. O(#V m) once (a pass over L W).
  // `left_out` (sorted vertex indices): vertices whose cross terms the clusters do not sum, because another term
  // holds them exactly (the factor preconditioner's stiffest vertices, rotation_terms.h). With any left out, the
  // instance serves rotation_terms() alone: its energy is no longer the Laplacian term's.
  RotationClusters(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                   const Eigen::MatrixXd& B, const VertexClusters& clusters, const std::vector<int>& left_out = {});

  void evaluate(const Eigen::MatrixXd& U, EnergyEvaluation& e) const override;
  void linearize(const Eigen::MatrixXd& U) override;
  Eigen::MatrixXd gradient(const EnergyEvaluation& e) const override;
  Eigen::MatrixXd product(const Eigen::MatrixXd& V) const override;
  // B (x) I3 + rotation_terms(), 3m x 3m (index axis * m + j).
  Eigen::MatrixXd dense_matrix() const override;
  // What the clusters' rotations add to the squares' B (x) I3 in the Gauss-Newton matrix at the linearised point,
  // 3m x 3m (index axis * m + j): sum_c Y_c^T M_c Y_c with Y_c of 6 rows (see the .cpp), O(27 #clusters m^2)
  // multiply-adds in dense blocks. The factor preconditioner of full integration adds it to N (x) I3
  // (docs/method.md section 11.1): on real cages it prices every vertex's rotation, where N prices none.
  // single_precision: the dense products in float (twice as fast; 1e-7 relative, enough for a preconditioner).
  Eigen::MatrixXd rotation_terms(bool single_precision = false) const;
  int sample_count() const override { return static_cast<int>(clusters_.samples.size()); }
  // Per cluster D_c and T_c times the block and their transposes back (36 m), and B times the block.
  double product_cost() const override {
    const double m = static_cast<double>(Z_.cols());
    return 36.0 * m * sample_count() + 3.0 * m * m;
  }
  double energy(const Eigen::MatrixXd& U) const;
  // The gradient of the squares' part alone, B U + b0: exact, the same in the full term.
  Eigen::MatrixXd squares_gradient(const Eigen::MatrixXd& U) const { return *B_ * U + b0_; }

 private:
  // Each cluster's 3 x m matrices are contiguous (row-major), so that a product reads each once, in cache.
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  // Cluster c's 3 x m rows of `rows` (D_ or Z_) times U (m by 3).
  Eigen::Matrix3d times_unknowns(const Rows& rows, Eigen::Index c, const Eigen::MatrixXd& U) const;
  // rotation_terms() with its dense products in Scalar.
  template <typename Scalar>
  Eigen::MatrixXd summed_terms() const;
  // A cluster's best rotation R_c at U, how it answers a change ((tr(S) I - S)^-1), and P_c = R_c (D_c U + e_c).
  struct ClusterTurn {
    Eigen::Matrix3d R, response, P;
  };
  // The turns of every cluster at the point U that energy() last evaluated.
  struct EvaluatedTurns {
    Eigen::MatrixXd U;
    std::vector<ClusterTurn> turns;
    Eigen::Index size() const { return static_cast<Eigen::Index>(turns.size()); }
    void resize(Eigen::Index k) {
      U.resize(0, 0);  // invalid until the evaluation is complete
      turns.resize(static_cast<size_t>(k));
    }
    ClusterTurn& turn(Eigen::Index c) { return turns[static_cast<size_t>(c)]; }
    const ClusterTurn& turn(Eigen::Index c) const { return turns[static_cast<size_t>(c)]; }
  };
  void turn_cluster(Eigen::Index c, const Eigen::MatrixXd& U, ClusterTurn& out) const;
  // The constant parts: D_c, e_c, K_c; and the one-rings' Z_c, a_c.
  void build_cross_terms(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& delta,
                         const Eigen::MatrixXd& SL_Xbar, const std::vector<int>& left_out);
  void build_rings(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& Xbar);
  // Each cluster's vertices in increasing order, those left out omitted.
  std::vector<std::vector<int>> cluster_members(const std::vector<int>& left_out) const;

  VertexClusters clusters_;
  const Eigen::MatrixXd* B_;
  Eigen::MatrixXd b0_;   // (S L W)^T (S L Xbar), m by 3
  double constant_ = 0;  // 1/2 (c0 + sum |delta_i|^2)
  Rows D_;               // D_c in rows 3c..3c+2, 3k by m
  Eigen::MatrixXd e_;    // e_c, 3k by 3
  Eigen::MatrixXd K_;    // K_c = sum_{i in c} |delta_i|^2 I - delta_i delta_i^T, 3k by 3
  Rows Z_;               // Z_c, 3k by m
  Eigen::MatrixXd a_;    // a_c, 3k by 3
  // At the linearised point: R_c, T_c = R_c Z_c, (tr(S_c) I - S_c)^-1, P_c = R_c M_c.
  Eigen::MatrixXd U_, R_, Hinv_, P_;
  Rows T_;
  // Kept by energy() (const: the line search evaluates trial points) for the next linearize(), whose point is
  // usually the last one evaluated: its SVDs and products are not made twice. energy() is not called concurrently.
  mutable EvaluatedTurns evaluated_;
};

// The relative error of the rule's gradient against the full Laplacian term's on `poses` held-out poses of the
// subspace (training_poses.h), relative to the part it approximates: |g_rule - g_full| / |g_cross| with g_cross =
// squares_gradient - g_full, the cross term's gradient (the squares' part is exact in both); the median over the
// poses, so that one extreme pose (a bump the clusters cannot follow) does not decide alone.
double cluster_test_error(RotationClusters& rule, const DeformationEnergy& energy, const BasisMatrix& W,
                          const Eigen::MatrixXd& U0, int poses, unsigned seed);

}  // namespace sd
