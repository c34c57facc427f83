// The rotation terms the factor preconditioner adds to N (x) I3 (gauss_newton_factor.h, docs/method.md section
// 11.1): what d delta_hat / dX adds to the Gauss-Newton matrix, exactly at the stiffest vertices (rotation_terms.h)
// and through rotation clusters at every other vertex (rotation_clusters.h, with the stiff vertices left out).
//
// Why both: N prices no vertex's rotation. On the hand bones a few hundred sliver vertices carry most of what it
// misses, and their exact terms leave PCG about 5 products per iteration; on the boy, the cow and the moomoo the
// missing part is spread over the whole surface, which the stiff vertices alone do not hold (6.5 to 8 products
// with a fresh factor) and a few hundred clusters do (1 to 4). Each costs the same per unit, 27 m^2 multiply-adds
// per vertex or cluster, so each gets its own budget.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/energy/deformation_energy.h"
#include "core/solver/internal/energy/rotation_terms.h"
#include "core/solver/internal/reduced/rotation_clusters.h"

namespace sd {

class FactorRotationTerms {
 public:
  // Multiply-adds allowed to each part's 3m x 3m sums (the stiff vertices', the clusters').
  static constexpr double kBudget = 1.2e9;
  // The clusters, at most: as many as the reduced integration's rule uses.
  static constexpr int kMaxClusters = 800;

  // Keeps references to the energy, W, U0 and B = (S L W)^T (S L W) (all must outlive this). `stiff`: the stiffest
  // vertices (vertex_stiffness.h), summed exactly. Clusters where the budget allows at least kMinClusters of them
  // and the mesh has several vertices per cluster (else the stiff vertices alone).
  FactorRotationTerms(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                      const Eigen::MatrixXd& B, const std::vector<int>& stiff);

  // The rotation terms at U, 3m x 3m (index axis * m + j).
  Eigen::MatrixXd matrix(const Eigen::MatrixXd& U);
  // Vertices and clusters summed: the factor's cost is 27 m^2 multiply-adds for each.
  int units() const { return exact_.vertex_count() + clusters(); }
  int clusters() const { return clusters_ ? clusters_->sample_count() : 0; }

  // The clusters the budget allows for a mesh of n vertices and m unknowns per axis (0: none).
  static int cluster_count(int n, int m);

 private:
  static constexpr int kMinClusters = 100;
  RotationTerms exact_;
  std::unique_ptr<RotationClusters> clusters_;
};

// The stiff vertices the budget allows (their limit for stiff_vertices) for m unknowns per axis.
int stiff_vertex_limit(int m);

}  // namespace sd
