// Poses of the subspace that the reduced integration's rule is tested on (rotation_clusters.h: cluster_test_error;
// An, Kim and James 2008 fit theirs on deformations the subspace will see). Each pose is a smooth deformation of the
// rest mesh (a bend about a hinge, a twist, a bump, a stretch or a taper, and combinations, with random axes and
// amplitudes up to 90 degrees and 15% of the diagonal) projected into the subspace by least squares on a subset of the
// vertices, so the same recipe serves the cage's W and the spectral basis. Deterministic: the same inputs and seed give
// the same poses on every platform and thread count.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/basis/basis_matrix.h"

namespace sd {

// `count` poses as unknowns U (m by 3 each; U0 the rest unknowns, W U0 = X0 up to the basis' precision).
std::vector<Eigen::MatrixXd> training_poses(const Vertices& X0, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                                            int count, unsigned seed);

// Uniform numbers in [0, 1) from a seed, the same on every platform (std's distributions are not).
class PortableRandom {
 public:
  explicit PortableRandom(unsigned seed) : state_(seed * 2654435761u + 1u) {}
  double uniform();  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int below(int n) { return static_cast<int>(uniform() * n); }  // [0, n)
  Eigen::Vector3d direction();                                  // a unit vector, uniform on the sphere
  double gaussian();

 private:
  unsigned long long state_;
};

}  // namespace sd
