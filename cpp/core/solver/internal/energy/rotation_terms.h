// The rotation terms of the Gauss-Newton matrix at a set of vertices (docs/method.md section 11.1): what
// d delta_hat / dX adds to those vertices' part of A = (M (W (x) I3))^T (M (W (x) I3)) beyond the constant
// (S L W)^T (S L W) (x) I3 that N already holds,
//   R(U) = sum_i (M_i W_i (x) I3)^T (M_i W_i (x) I3) - ((S L)_i W_i)^T ((S L)_i W_i) (x) I3,
// at the point X = X0 + W (U - U0). N (x) I3 + R is A exactly on those vertices and N's estimate elsewhere:
// the factor preconditioner (gauss_newton_factor.h) of the full-integration fast step.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/energy/laplacian_coordinates.h"
#include "core/solver/internal/energy/laplacian_rows.h"

namespace sd {

class RotationTerms {
 public:
  // Keeps no reference: the vertices' rows of the Laplacian terms and of W are copied (a few hundred rows).
  RotationTerms(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                const std::vector<int>& vertices);

  // R(U), 3m x 3m (index axis * m + j). O(#vertices m^2).
  Eigen::MatrixXd matrix(const Eigen::MatrixXd& U) const;
  int vertex_count() const { return static_cast<int>(weights_.size()); }

 private:
  LaplacianCoordinates rows_;
  Eigen::MatrixXd W_local_;  // W's rows at the vertices' one-rings (dense: a few thousand rows)
  Vertices X0_local_;
  Eigen::MatrixXd U0_;
  Eigen::VectorXd weights_;  // 1 per vertex: each is summed exactly
};

}  // namespace sd
