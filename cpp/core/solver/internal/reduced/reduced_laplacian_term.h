// The Laplacian term of the subspace problem as a reduced integration computes it (reduced_subspace.h): its value,
// gradient and Gauss-Newton matrix in the unknowns U (m by 3, X = X0 + W (U - U0)) without a pass over W. Two rules:
//   - SampledLaplacian (sampled_laplacian.h): the term at sampled vertices with weights; with every vertex a sample
//     of weight 1 the exact sum (the rule for meshes of at most max(800, 2m) vertices);
//   - RotationClusters (rotation_clusters.h): the term's squares exact and its cross term with one rotation per
//     cluster of vertices; the rule for meshes larger than that.
#pragma once

#include <Eigen/Core>

#include "core/solver/internal/energy/deformation_energy.h"

namespace sd {

class ReducedLaplacianTerm {
 public:
  virtual ~ReducedLaplacianTerm() = default;
  // e.laplacian_energy (and, where the rule has them, e.laplacian_residual) at U.
  virtual void evaluate(const Eigen::MatrixXd& U, EnergyEvaluation& e) const = 0;
  // Sets the point of gradient(), product() and dense_matrix().
  virtual void linearize(const Eigen::MatrixXd& U) = 0;
  // The gradient in U at the linearised point, m by 3; e: the evaluation there.
  virtual Eigen::MatrixXd gradient(const EnergyEvaluation& e) const = 0;
  // The Gauss-Newton matrix times V (m by 3s).
  virtual Eigen::MatrixXd product(const Eigen::MatrixXd& V) const = 0;
  // The same as a dense 3m x 3m matrix (index axis * m + j).
  virtual Eigen::MatrixXd dense_matrix() const = 0;
  // The vertices the rule reads: the samples, or the clusters' centres.
  virtual int sample_count() const = 0;
  // Multiply-adds of product() on one m by 3 block (what the factor preconditioner weighs its products by).
  virtual double product_cost() const = 0;
};

}  // namespace sd
