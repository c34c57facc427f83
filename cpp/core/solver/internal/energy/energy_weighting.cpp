#include "core/solver/internal/energy/energy_weighting.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/mesh/mass_matrix.h"

namespace sd {

EnergyWeights::EnergyWeights(const Vertices& X0, const Faces& F)
    : areas_(lumped_mass(X0, F)), reference_area_(areas_.sum() / kReferenceVertexCount) {}

Eigen::VectorXd EnergyWeights::laplacian_row_scales(EnergyWeighting weighting) const {
  if (weighting == EnergyWeighting::Uniform) return Eigen::VectorXd::Ones(areas_.size());
  return (reference_area_ / areas_.array()).sqrt();
}

Eigen::VectorXd EnergyWeights::handle_coefficients(EnergyWeighting weighting, const std::vector<int>& vertices,
                                                   const std::vector<int>& group_sizes) const {
  Eigen::VectorXd c = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(vertices.size()));
  if (weighting == EnergyWeighting::Uniform) return c;
  size_t first = 0;
  for (int size : group_sizes) {
    if (size < 0 || first + size > vertices.size())
      throw Error("energy weights: handle groups of " + std::to_string(first + size) + " vertices for " +
                  std::to_string(vertices.size()) + " handle vertices");
    double group_area = 0.0;
    for (size_t k = first; k < first + size; ++k) group_area += areas_[vertices[k]];
    // The group's pull: the reference vertices it covers, at least one; spread over its vertices by area.
    const double pull = std::max(group_area, reference_area_) / reference_area_;
    for (size_t k = first; k < first + size; ++k)
      c[static_cast<Eigen::Index>(k)] = pull * areas_[vertices[k]] / group_area;
    first += size;
  }
  if (first != vertices.size())
    throw Error("energy weights: handle groups of " + std::to_string(first) + " vertices for " +
                std::to_string(vertices.size()) + " handle vertices");
  return c;
}

}  // namespace sd
