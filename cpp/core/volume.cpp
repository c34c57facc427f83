#include "core/volume.h"

namespace sd {

double signed_volume(const Vertices& V, const Faces& F) {
  // Divergence theorem: each triangle contributes the signed volume of its tetrahedron with the origin.
  double sum = 0.0;
  for (int f = 0; f < F.rows(); ++f)
    sum += V.row(F(f, 0)).cross(V.row(F(f, 1))).dot(V.row(F(f, 2)));
  return sum / 6.0;
}

Vertices volume_gradient(const Vertices& V, const Faces& F) {
  // Report eq. 10: d((a x b).c) = (b x c) da + (c x a) db + (a x b) dc (the triple product is cyclic).
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

}  // namespace sd
