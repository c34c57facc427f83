#include "core/solver/internal/steps/factor_rotation_terms.h"

#include <algorithm>

namespace sd {
namespace {

// Units (vertices or clusters) whose 27 m^2 multiply-adds fit the budget.
int units_within_budget(int m) {
  return static_cast<int>(FactorRotationTerms::kBudget / (27.0 * m * static_cast<double>(m)));
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

}  // namespace

int stiff_vertex_limit(int m) { return std::min(1000, units_within_budget(m)); }

int FactorRotationTerms::cluster_count(int n, int m) {
  // Four per cage vertex: the unknowns' rotations vary no faster over the surface than the cage does.
  const int k = std::min({kMaxClusters, units_within_budget(m), std::max(kMinClusters, 4 * m)});
  // A cluster needs several vertices to stand for (else the stiff vertices and N serve as well).
  return k >= kMinClusters && n >= 4 * k ? k : 0;
}

FactorRotationTerms::FactorRotationTerms(const DeformationEnergy& energy, const BasisMatrix& W,
                                         const Eigen::MatrixXd& U0, const Eigen::MatrixXd& B,
                                         const std::vector<int>& stiff)
    : exact_(energy, W, U0, stiff) {
  const int k = cluster_count(energy.vertex_count(), static_cast<int>(W.cols()));
  if (k > 0)
    clusters_ = std::make_unique<RotationClusters>(
        energy, W, U0, B, surface_clusters(energy.rest_positions(), energy.coordinates(), k), sorted(stiff));
}

Eigen::MatrixXd FactorRotationTerms::matrix(const Eigen::MatrixXd& U) {
  Eigen::MatrixXd R = exact_.matrix(U);
  if (clusters_) {
    clusters_->linearize(U);
    R += clusters_->rotation_terms(/*single_precision=*/true);  // a preconditioner's: half the time
  }
  return R;
}

}  // namespace sd
