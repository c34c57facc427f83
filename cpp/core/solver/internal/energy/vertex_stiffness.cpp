#include "core/solver/internal/energy/vertex_stiffness.h"

#include <algorithm>
#include <numeric>

#include "core/solver/internal/reduced/training_poses.h"

namespace sd {

Eigen::VectorXd vertex_stiffness(const DeformationEnergy& energy, const BasisMatrix& W, int probes) {
  PortableRandom random(7);
  Eigen::MatrixXd Z(W.cols(), 3 * probes);
  for (Eigen::Index k = 0; k < Z.size(); ++k) Z.data()[k] = random.gaussian();
  Eigen::MatrixXd images;
  W.multiply(Z, images);
  EnergyJacobian J(energy);
  energy.update_jacobian(energy.rest_positions(), J);
  return J.laplacian_rows(images).rowwise().squaredNorm() / probes;
}

std::vector<int> stiff_vertices(const DeformationEnergy& energy, const Eigen::VectorXd& stiffness, double ratio,
                                int limit) {
  const Eigen::VectorXd& area = energy.weights().vertex_areas();
  const double mean_density = stiffness.sum() / area.sum();
  std::vector<int> out;
  for (Eigen::Index i = 0; i < stiffness.size(); ++i)
    if (stiffness[i] > ratio * mean_density * area[i]) out.push_back(static_cast<int>(i));
  // Stiffest first; ties by index, so the order (and so every sum over these) is the same on every platform.
  std::sort(out.begin(), out.end(), [&](int a, int b) {
    const double da = stiffness[a] / area[a], db = stiffness[b] / area[b];
    return da != db ? da > db : a < b;
  });
  if (static_cast<int>(out.size()) > limit) out.resize(static_cast<size_t>(std::max(limit, 0)));
  return out;
}

}  // namespace sd
