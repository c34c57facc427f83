#include "core/mesh/cotan_laplacian.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// cot of the angle at `apex` in the triangle (apex, p, q): (p - apex).(q - apex) / |(p - apex) x (q - apex)|.
// Throws on a zero-area triangle: its cotangents are infinite and would poison every solve downstream.
double cot_at(const Eigen::RowVector3d& apex, const Eigen::RowVector3d& p, const Eigen::RowVector3d& q, int face) {
  const Eigen::RowVector3d u = p - apex, v = q - apex;
  const double sine_term = u.cross(v).norm();  // |u||v| sin(angle), twice the triangle's area
  if (!(sine_term > 0.0) || !std::isfinite(sine_term))
    throw Error(ErrorCode::InvalidMesh, "cotan Laplacian: triangle " + std::to_string(face) +
                                            " is degenerate (zero area or non-finite coordinates)");
  return u.dot(v) / sine_term;
}

}  // namespace

Eigen::SparseMatrix<double> cotan_laplacian(const Vertices& V, const Faces& F) {
  const int n = static_cast<int>(V.rows());
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<size_t>(F.rows()) * 12);
  for (int f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int idx = F(f, k);
      if (idx < 0 || idx >= n)
        throw Error(ErrorCode::InvalidMesh, "cotan Laplacian: triangle " + std::to_string(f) + " has vertex index " +
                                                std::to_string(idx) + " outside [0, " + std::to_string(n) + ")");
    }
    // The angle at corner k is opposite the edge (k+1, k+2); each triangle adds half of it to that edge.
    for (int k = 0; k < 3; ++k) {
      const int c = F(f, k), a = F(f, (k + 1) % 3), b = F(f, (k + 2) % 3);
      const double w = 0.5 * cot_at(V.row(c), V.row(a), V.row(b), f);
      entries.emplace_back(a, b, w);
      entries.emplace_back(b, a, w);
      entries.emplace_back(a, a, -w);
      entries.emplace_back(b, b, -w);
    }
  }
  // Negative cotangents (obtuse angles) are kept: the matrix stays the exact P1 finite-element stiffness
  // matrix (up to sign), which is negative semidefinite whatever the signs of its off-diagonal entries.
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(entries.begin(), entries.end());  // duplicates are summed
  L.makeCompressed();
  return L;
}

}  // namespace sd
