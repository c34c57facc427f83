#include "core/basis/cage_quality.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"
#include "core/mesh/volume.h"
#include "core/parts/part_volume.h"
#include "core/parallel/parallel_for.h"
#include "core/timer.h"
#include "core/basis/basis_gram.h"

namespace sd {
namespace {

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2g", x);
  return text;
}

// max_i |W_ij| for every column j (blocks of rows, combined by max: the same with any thread count).
Eigen::VectorXd column_maxima(const BasisMatrix& W) {
  const int m = W.cols();
  return parallel::parallel_reduce(
      0, W.rows(), 1024, Eigen::VectorXd(Eigen::VectorXd::Zero(m)),
      [&](int lo, int hi) {
        Eigen::VectorXd part = Eigen::VectorXd::Zero(m);
        for (int i = lo; i < hi; ++i)
          for (int j = 0; j < m; ++j) part[j] = std::max(part[j], std::abs(W.get(i, j)));
        return part;
      },
      [](Eigen::VectorXd a, const Eigen::VectorXd& b) { return Eigen::VectorXd(a.cwiseMax(b)); });
}

}  // namespace

CageQuality cage_quality(const BasisMatrix& W, const Mesh& mesh, const Mesh& cage, const CageQualityOptions& o) {
  const double t0 = now_ms();
  const int n = W.rows(), m = W.cols();
  if (n != mesh.V.rows() || m != cage.V.rows())
    throw Error("cage quality: W is " + std::to_string(n) + " x " + std::to_string(m) + " for a mesh of " +
                std::to_string(mesh.V.rows()) + " vertices and a cage of " + std::to_string(cage.V.rows()));
  CageQuality q;
  q.cage_vertices = m;
  if (m > 0 && n > 0) {
    const Eigen::VectorXd maxima = column_maxima(W);
    q.min_column_max = maxima.minCoeff();
    q.weak_vertices = static_cast<int>((maxima.array() < o.weak_weight).count());
  }
  const double mesh_volume = enclosed_volume(mesh.V, mesh.F);
  q.volume_ratio = mesh_volume > 0 ? signed_volume(cage.V, cage.F) / mesh_volume : 0;

  if (n > 0 && m > 0 && m <= o.max_spectrum_vertices) {
    const long long wanted = std::max<long long>({1, o.sample_rows, static_cast<long long>(o.rows_per_vertex) * m});
    const int stride = static_cast<int>(std::max<long long>(1, (n + wanted - 1) / wanted));
    q.sampled_rows = (n + stride - 1) / stride;
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(basis_gram(W, stride, q.sampled_rows) / q.sampled_rows,
                                                               Eigen::EigenvaluesOnly);
    const Eigen::VectorXd& lambda = eigen.eigenvalues();  // ascending
    const double largest = lambda[m - 1];
    if (eigen.info() == Eigen::Success && largest > 0) {
      q.influence_ratio = std::max(0.0, lambda[0]) / largest;
      q.weak_motions = static_cast<int>((lambda.array() < o.min_influence_ratio * largest).count());
    }
  }

  const auto warn = [&](const char* code, const std::string& sentence) {
    q.warning_codes.push_back(code);
    q.warnings.push_back(sentence);
  };
  if (m > 0 && q.weak_vertices > o.max_weak_fraction * m)
    warn("weak_cage_vertices", std::to_string(q.weak_vertices) + " of the " + std::to_string(m) +
                                   " cage vertices have no weight above " + number(o.weak_weight) +
                                   " on any mesh vertex: moving them barely moves the mesh");
  if (q.influence_ratio < o.min_influence_ratio)  // false for NaN (not computed)
    warn("weak_cage_motions", std::to_string(q.weak_motions) + (q.weak_motions == 1 ? " motion" : " motions") +
                                  " of the cage barely move the mesh (influence ratio " + number(q.influence_ratio) +
                                  ", below " + number(o.min_influence_ratio) +
                                  "): the deformed cage can drift far from the mesh");
  if (q.volume_ratio > o.max_volume_ratio)
    warn("loose_cage", "the cage encloses " + number(q.volume_ratio) + " times the mesh's volume (a loose cage)");
  q.ms = now_ms() - t0;
  return q;
}

}  // namespace sd
