// Where the Laplacian term's Gauss-Newton matrix has its weight (docs/method.md section 11.1).
//
// Vertex i's share of A's Laplacian part at rest is |M_i (W (x) I3)|_F^2 (M_i: its three rows of the Jacobian
// M = S L (x) I3 - d delta_hat / dX). On real meshes it is far from even: on the hand bones model 6 vertices of
// 5,497 (slivers, whose cotangents and 1/|d_i| are large) hold 85% of its trace. Such vertices are what the
// constant preconditioner N misjudges most (their rotation terms are as large as their Laplacian rows), and what
// an area-based quadrature misses; the solver sums them exactly in both places.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/basis/basis_matrix.h"
#include "core/solver/internal/energy/deformation_energy.h"

namespace sd {

// |M_i (W (x) I3)|_F^2 for every vertex, estimated from `probes` Gaussian directions z of the unknowns
// (E |M_i W z|^2 is the squared norm); one pass over W for all of them. Fixed seed: the same on every platform.
Eigen::VectorXd vertex_stiffness(const DeformationEnergy& energy, const BasisMatrix& W, int probes = 8);

// The vertices whose stiffness per area exceeds `ratio` times the surface's mean, stiffest first, at most `limit`.
std::vector<int> stiff_vertices(const DeformationEnergy& energy, const Eigen::VectorXd& stiffness, double ratio,
                                int limit);

}  // namespace sd
