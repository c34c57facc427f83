// Reduced integration of the Laplacian term (docs/method.md section 17): the sum over every vertex,
// E_lap = sum_i e_i(X), e_i = 1/2 |s_i ((L X)_i - delta_hat_i(X))|^2, replaced by a sum over samples s of
// w_s e_s(X) with weights w_s >= 0, chosen once per session (An, Kim and James 2008, "Optimizing cubature for
// efficient integration of subspace deformations").
//
// Samples: spread over the surface by farthest-point sampling (on every vertex, or a random pool of
// kSpreadPool on larger meshes); each sample's prior weight is the area of its cell (the pool vertices nearest to
// it) over its own area, a quadrature rule that integrates any smooth energy density. The weights are then
// fitted on training poses of the subspace (training_poses.h): on each pose the energy and its derivative along
// `directions` random directions of the unknowns (An et al. match reduced forces; random projections of them keep
// the fit small), each pose's rows scaled to unit size, by non-negative least squares on w = prior x v with a
// Tikhonov pull of v towards 1, so the fit corrects the quadrature without overfitting the poses. Held-out poses
// measure the result (test_error).
//
// Selection::Greedy is An et al.'s own selection, greedy NNLS over a random candidate pool (nnls.h), kept for
// comparison: on the built-in bar and sphere its shapes were 10x further from the full solve's (method.md 17).
// Meshes with at most max_samples vertices get every vertex with weight 1: the sum is then exact.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct CubatureOptions {
  enum class Selection { Spread, Greedy };
  Selection selection = Selection::Spread;
  int max_samples = 800;
  // Vertices summed exactly, with weight 1 (at most max_samples / 2 of them, the first ones): those whose terms a
  // quadrature by area cannot represent (vertex_stiffness.h). The spread samples cover the rest of the surface.
  std::vector<int> exact_vertices;
  // Poses to fit the weights on (0: the spread samples' quadrature weights, unfitted). The fit is off by default:
  // on the benchmark capsules it left the reduced shape further from the full one than the quadrature did
  // (docs/method.md section 17) and costs two full evaluations per pose.
  int training_poses = 0;
  int test_poses = 4;
  int directions = 16;       // derivative rows per pose
  double prior_pull = 1e-2;  // Tikhonov weight of w = prior, relative to the fit's mean column norm^2
  int greedy_candidates = 6000;
  unsigned seed = 1;
};

struct Cubature {
  std::vector<int> samples;  // vertex indices, increasing
  Eigen::VectorXd weights;   // one per sample, > 0: the Laplacian term's
  // One per sample: the plain quadrature rule (its cell's area over its own; 1 where every vertex is a sample).
  // It integrates any smooth density, such as the volume's gradient, the reduced step's constraint direction.
  Eigen::VectorXd quadrature;
  double training_error = 0;  // relative error of the fit on its training poses (0 without a fit)
  double test_error = 0;      // the same on held-out poses
  int candidates = 0;         // vertices the samples were chosen among
  int exact = 0;              // samples of exact_vertices (weight 1)
  double ms = 0;              // time of the choice and the fit
};

// Chooses the samples and weights of `energy`'s Laplacian term (at its current weighting) for the subspace W
// (unknowns U0 at rest, X = X0 + W (U - U0)).
Cubature fit_cubature(const DeformationEnergy& energy, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                      const CubatureOptions& options = {});

}  // namespace sd
