// The Laplacian term summed over sampled vertices with weights: E(U) = 1/2 sum_s w_s |r_s(X)|^2, with the samples'
// one-rings' rows of W (W_S) giving their positions, residuals and Jacobian rows M_S, so the Gauss-Newton products
// W_S^T M_S^T Omega M_S W_S V read W_S alone (Omega: the weights). The reduced integration uses it with every
// vertex a sample of weight 1 (a mesh of at most max(800, 2m) vertices: the sum is exact).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/solver/internal/energy/laplacian_rows.h"
#include "core/solver/internal/reduced/reduced_laplacian_term.h"

namespace sd {

class SampledLaplacian : public ReducedLaplacianTerm {
 public:
  // samples: distinct vertices; weights: one per sample, > 0.
  SampledLaplacian(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                   const std::vector<int>& samples, const Eigen::VectorXd& weights);

  // Sets e.laplacian_residual (the samples' rows) and e.laplacian_energy.
  void evaluate(const Eigen::MatrixXd& U, EnergyEvaluation& e) const override;
  void linearize(const Eigen::MatrixXd& U) override;
  // W_S^T M_S^T Omega r_S from the samples' residual in e.
  Eigen::MatrixXd gradient(const EnergyEvaluation& e) const override;
  Eigen::MatrixXd product(const Eigen::MatrixXd& V) const override;
  Eigen::MatrixXd dense_matrix() const override;
  int sample_count() const override { return static_cast<int>(weights_.size()); }
  // W_S forward and transposed, 3 columns each.
  double product_cost() const override { return 6.0 * W_local_.rows() * static_cast<double>(W_local_.cols()); }

 private:
  // Positions of the samples' columns for unknowns U.
  Vertices local_positions(const Eigen::MatrixXd& U) const;

  Eigen::MatrixXd U0_;
  LaplacianCoordinates sampled_;  // the samples' rows of the Laplacian terms
  std::vector<int> columns_;      // the vertices they touch
  BasisMatrix W_local_;           // W's rows at those vertices
  Vertices X0_local_;             // their rest positions
  Eigen::VectorXd weights_;       // one per sample
  LaplacianRows M_;               // the samples' Jacobian rows at the linearised point
};

}  // namespace sd
