#include "core/mesh/volume.h"

#include <cmath>
#include <limits>

#include "core/parallel/parallel_for.h"

namespace sd {
namespace {

// Triangles per task of the sums, and vertices per task of the gradient.
constexpr int kTriangleBlock = 4096;
constexpr int kVertexBlock = 2048;

// Six times the signed volume of the tetrahedron of triangle f with o (the corners taken relative to o, so that
// the terms are of the model's size wherever it sits).
double tetrahedron6(const Vertices& V, const Faces& F, int f, const VolumeReference& o) {
  const Eigen::RowVector3d a = V.row(F(f, 0)) - o, b = V.row(F(f, 1)) - o, c = V.row(F(f, 2)) - o;
  return a.cross(b).dot(c);
}

}  // namespace

VolumeReference volume_reference(const Vertices& V, const Faces& F) {
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Eigen::RowVector3d p = V.row(F(f, k));
      if (!p.allFinite()) continue;
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  if (!(lo.array() <= hi.array()).all()) return VolumeReference::Zero();
  // The centre snapped to a grid of spacing s, the power of two at or above the diagonal: a model within s/2 of the
  // origin gets o = 0 exactly, so its sums are bit for bit those about the origin (its shapes, their hashes and its
  // cages stay as they were), and any other a point within s/2 of its centre, where the terms stay of its size.
  const VolumeReference centre = 0.5 * (lo + hi);
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0) || !std::isfinite(diagonal)) return centre;
  const double s = std::exp2(std::ceil(std::log2(diagonal)));
  return (centre / s).array().round().matrix() * s;
}

double signed_volume(const Vertices& V, const Faces& F) { return signed_volume(V, F, volume_reference(V, F)); }

double signed_volume(const Vertices& V, const Faces& F, const VolumeReference& o) {
  // Divergence theorem: each triangle contributes the signed volume of its tetrahedron with o.
  const double sum = parallel::parallel_sum(0, static_cast<int>(F.rows()), kTriangleBlock, [&](int lo, int hi) {
    double s = 0.0;
    for (int f = lo; f < hi; ++f) s += tetrahedron6(V, F, f, o);
    return s;
  });
  return sum / 6.0;
}

Eigen::VectorXd signed_volumes(const Vertices& V, const Faces& F, const std::vector<int>& label, int count,
                               const VolumeReference& o) {
  const Eigen::VectorXd sum = parallel::parallel_reduce(
      0, static_cast<int>(F.rows()), kTriangleBlock, Eigen::VectorXd(Eigen::VectorXd::Zero(count)),
      [&](int lo, int hi) {
        Eigen::VectorXd s = Eigen::VectorXd::Zero(count);
        for (int f = lo; f < hi; ++f) s[label[f]] += tetrahedron6(V, F, f, o);
        return s;
      },
      [](Eigen::VectorXd a, const Eigen::VectorXd& b) { return Eigen::VectorXd(a + b); });
  return sum / 6.0;
}

VertexTriangles vertex_triangles(int vertex_count, const Faces& F) {
  VertexTriangles out;
  out.start.assign(static_cast<size_t>(vertex_count) + 1, 0);
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++out.start[static_cast<size_t>(F(f, k)) + 1];
  for (int v = 0; v < vertex_count; ++v) out.start[v + 1] += out.start[v];
  std::vector<int> fill(out.start.begin(), out.start.end() - 1);
  out.triangle.resize(3 * static_cast<size_t>(F.rows()));
  out.corner.resize(out.triangle.size());
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int s = fill[F(f, k)]++;
      out.triangle[s] = f;
      out.corner[s] = k;
    }
  return out;
}

Vertices volume_gradient(const Vertices& V, const Faces& F) {
  return volume_gradient(V, F, vertex_triangles(static_cast<int>(V.rows()), F), volume_reference(V, F));
}

Vertices volume_gradient(const Vertices& V, const Faces& F, const VertexTriangles& around, const VolumeReference& o) {
  // docs/method.md section 5: d((a x b).c) = (b x c) da + (c x a) db + (a x b) dc (the triple product is cyclic), so
  // the gradient at a vertex sums, over its triangles, the cross product of the two corners after it (relative to
  // o: about the origin, a far model's products would cancel to the gradient's size as the volume's terms do).
  Vertices G(V.rows(), 3);
  parallel::parallel_for(0, static_cast<int>(V.rows()), kVertexBlock, [&](int lo, int hi) {
    for (int v = lo; v < hi; ++v) {
      Eigen::RowVector3d g = Eigen::RowVector3d::Zero();
      for (int s = around.start[v]; s < around.start[v + 1]; ++s) {
        const int f = around.triangle[s], k = around.corner[s];
        g += (V.row(F(f, (k + 1) % 3)) - o).cross(V.row(F(f, (k + 2) % 3)) - o);
      }
      G.row(v) = g / 6.0;
    }
  });
  return G;
}

std::array<double, 4> volume_along(const Vertices& V, const Vertices& D, const Faces& F, const VolumeReference& o) {
  // (a + t da) x (b + t db) . (c + t dc), expanded by powers of t, summed over the triangles; a, b, c relative to o
  // (the directions are differences already).
  using Coefficients = std::array<double, 4>;
  Coefficients k = parallel::parallel_reduce(
      0, static_cast<int>(F.rows()), kTriangleBlock, Coefficients{0.0, 0.0, 0.0, 0.0},
      [&](int lo, int hi) {
        Coefficients p{0.0, 0.0, 0.0, 0.0};
        for (int f = lo; f < hi; ++f) {
          const Eigen::RowVector3d a = V.row(F(f, 0)) - o, b = V.row(F(f, 1)) - o, c = V.row(F(f, 2)) - o;
          const Eigen::RowVector3d da = D.row(F(f, 0)), db = D.row(F(f, 1)), dc = D.row(F(f, 2));
          const Eigen::RowVector3d ab = a.cross(b), dadb = da.cross(db), adb_dab = a.cross(db) + da.cross(b);
          p[0] += ab.dot(c);
          p[1] += adb_dab.dot(c) + ab.dot(dc);
          p[2] += dadb.dot(c) + adb_dab.dot(dc);
          p[3] += dadb.dot(dc);
        }
        return p;
      },
      [](Coefficients a, const Coefficients& b) {
        for (int i = 0; i < 4; ++i) a[i] += b[i];
        return a;
      });
  for (double& x : k) x /= 6.0;
  return k;
}

}  // namespace sd
