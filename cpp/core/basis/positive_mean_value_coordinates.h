// Positive mean value coordinates (Lipman, Kopf, Cohen-Or and Levin 2007, "GPU-assisted positive mean value
// coordinates for mesh deformations") of points with respect to a closed, outward triangle cage:
//   w_j(x) = V_j(x) / sum_k V_k(x),   V_j(x) = integral over the unit sphere around x of phi_j(y1) / |y1 - x|,
// y1 = the first point where the ray from x in that direction meets the cage (phi_j: the hat function of cage
// vertex j). Mean value coordinates integrate over every crossing of the ray, with alternating signs, and go
// negative where the cage is concave; keeping only the part of the cage x sees makes every weight >= 0.
//   W is #points by #cage vertices; rows sum to 1 and entries are >= 0 (to rounding: exactly >= 0 as stored).
//   Linear precision (W P0 = points) holds where x sees the whole cage (a convex cage: there W equals mean value
//   coordinates to rounding) and not elsewhere; the weights are continuous but not smooth where what x sees
//   changes (docs/method.md section 18 measures both).
//
// How (docs/method.md section 18): the first crossing is always on a front-facing triangle (x on its inner
// side), and a front-facing triangle is hidden exactly where a back-facing one lies in front of it. So
//   V = sum over front-facing triangles of their mean value integrals (closed form, as mean value coordinates)
//     - for each back-facing triangle B, the integral over B's projection of phi(y') / |y' - x|,
// y' the next crossing behind B (which a front-facing triangle holds). Only that correction is sampled: B is
// cut into cells of at most `cell solid angle` each, one ray per cell finds the triangle T behind its centre,
// and the cell's part of T's integral is subtracted in closed form (the cell's mean vector
// m = integral of the direction over the cell, and T's linear functions: sum_k c_k (p_k - x) = m). A cage
// every point sees entirely has no back-facing triangles: no rays at all.
#pragma once

#include "core/mesh/mesh.h"
#include "core/basis/mean_value_coordinates.h"
#include "core/basis/basis_matrix.h"

namespace sd {

struct PositiveMvcOptions {
  // Sampling of the hidden parts: cells of at most 4 pi / (6 resolution^2) steradians, the solid angle of a
  // pixel of a cube map with resolution^2 pixels per face (the paper rasterises such a cube map per point).
  int resolution = 32;
  static constexpr int kMinResolution = 2;
  static constexpr int kMaxResolution = 1024;
};

struct PositiveMvcReport {
  double rays = 0;          // rays cast (one per cell), over all points
  double hidden_faces = 0;  // back-facing triangles corrected, over all points
  double clamped = 0;       // weights below 0 after the correction (sampling error), set to 0
  double clamped_mass = 0;  // the sum of those weights' magnitudes, each relative to its row's sum
};

// W (#points by #cage vertices). Throws sd::Error as mean_value_coordinates does (points outside the cage,
// the memory budget, bad cage indices, cancellation), and for a resolution outside [2, 1024]. `report`, when
// given, receives the minimum weight and counts; `sampling` the rays cast.
BasisMatrix positive_mean_value_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                                            const PositiveMvcOptions& options = {}, MvcReport* report = nullptr,
                                            PositiveMvcReport* sampling = nullptr);

}  // namespace sd
