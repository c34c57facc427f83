#include "core/mesh/volume.h"

namespace sd {

double signed_volume(const Vertices& V, const Faces& F) {
  // Divergence theorem: each triangle contributes the signed volume of its tetrahedron with the origin.
  double sum = 0.0;
  for (int f = 0; f < F.rows(); ++f)
    sum += V.row(F(f, 0)).cross(V.row(F(f, 1))).dot(V.row(F(f, 2)));
  return sum / 6.0;
}

Vertices volume_gradient(const Vertices& V, const Faces& F) {
  // docs/method.md section 5: d((a x b).c) = (b x c) da + (c x a) db + (a x b) dc (the triple product is cyclic).
  Vertices G = Vertices::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0), b = F(f, 1), c = F(f, 2);
    const Eigen::RowVector3d xa = V.row(a), xb = V.row(b), xc = V.row(c);
    G.row(a) += xb.cross(xc);
    G.row(b) += xc.cross(xa);
    G.row(c) += xa.cross(xb);
  }
  G /= 6.0;
  return G;
}

std::array<double, 4> volume_along(const Vertices& V, const Vertices& D, const Faces& F) {
  // (a + t da) x (b + t db) . (c + t dc), expanded by powers of t, summed over the triangles.
  std::array<double, 4> k{0.0, 0.0, 0.0, 0.0};
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::RowVector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d da = D.row(F(f, 0)), db = D.row(F(f, 1)), dc = D.row(F(f, 2));
    const Eigen::RowVector3d ab = a.cross(b), dadb = da.cross(db), adb_dab = a.cross(db) + da.cross(b);
    k[0] += ab.dot(c);
    k[1] += adb_dab.dot(c) + ab.dot(dc);
    k[2] += dadb.dot(c) + adb_dab.dot(dc);
    k[3] += dadb.dot(dc);
  }
  for (double& x : k) x /= 6.0;
  return k;
}

}  // namespace sd
