// How well conditioned the Gauss-Newton step's normal matrix is (for the experiments: the project report argues
// that the subspace lowers kappa(J_f^T J_f); docs/experiments measures it). At positions X:
//   full space: H = J_f^T J_f (3#V by 3#V, sparse): its largest eigenvalue by Lanczos, its smallest by
//               shift-invert Lanczos (Spectra), kappa = largest / smallest;
//   subspace:   A = (J_f (W (x) I3))^T (J_f (W (x) I3)) (3m by 3m, dense): all eigenvalues. kappa(A) depends on the
//               basis W as well as on the subspace; in_orthonormal_basis measures the same operator in an
//               orthonormal basis of span(W) instead (the generalized eigenvalues of A against W^T W (x) I3),
//               which isolates the subspace's own effect. By Cauchy interlacing that one is never above the full
//               space's kappa.
// Both leave out the bones' straightness term (the experiments measure the energy of the report, without it).
#pragma once

#include "core/solver/internal/energy/deformation_energy.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct StepConditioning {
  double smallest = 0;   // smallest eigenvalue
  double largest = 0;    // largest eigenvalue
  double condition = 0;  // largest / smallest (infinite when the smallest is not positive)
};

// The energy's handles and targets must be set. Throws sd::Error when a Lanczos run does not converge or the
// dense matrix would exceed memory_budget_bytes.
StepConditioning full_space_conditioning(const DeformationEnergy& energy, const Vertices& X);
StepConditioning subspace_conditioning(const DeformationEnergy& energy, const BasisMatrix& W, const Vertices& X,
                                       bool in_orthonormal_basis, double memory_budget_bytes = 1e9);

}  // namespace sd
