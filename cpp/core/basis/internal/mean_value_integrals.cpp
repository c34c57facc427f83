#include "core/basis/internal/mean_value_integrals.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "core/error.h"

namespace sd {
namespace {

constexpr double kPi = 3.14159265358979323846;
// A point closer than this (times the cage's bounding-box diagonal) to a cage vertex gets the delta row.
constexpr double kOnVertex = 1e-12;
// |det(u0, u1, u2)| below this: the point is close to the plane of the triangle. Beside the triangle,
// the general formula then loses accuracy (its numerator is O(det^2) but is computed from O(1) terms,
// an absolute error ~eps/|det| in the weights, 1e-10 of the size at det ~ 1e-9 on the real cages), so
// such "thin" triangles use thin_triangle_weights below. JSW's robust version drops them instead (exact
// in the plane, but an O(det) error near it).
constexpr double kThin = 1e-6;
// |det| below this and the point over the triangle: the point is on the triangle (JSW "pi - h < eps").
constexpr double kOnFace = 1e-13;
// |det| at which thin triangles are evaluated (see thin_triangle_weights).
constexpr double kThinTarget = 1e-5;
// pi - h below this (h = half the perimeter of the spherical triangle): the point is over the triangle
// (the three arcs make a full great circle), not beside it. Over the triangle the general formula stays
// accurate however close the point is: there the numerator does not cancel.
constexpr double kOverTriangle = 1e-6;

// JSW 2005's weights of one triangle (section 3.3 pseudo-code) from the arcs theta_k opposite vertex k,
// their sines and cosines and det = det[u0 u1 u2], without the factor 1/(2 d_k):
//   w_k = (theta_k - a_{k+1} theta_{k+2} - a_{k+2} theta_{k+1}) sin(theta_k) / det,
// a_k = cos of the spherical triangle's angle at u_k (JSW's c_k) by the spherical law of cosines. This is
// JSW's (...) / (sin theta_{k+1} s_{k+2}) with s_{k+2} = det / (sin theta_k sin theta_{k+1}): taking the
// sine of the angle from the determinant rather than sqrt(1 - c^2) keeps full accuracy near the plane.
inline void triangle_weights(const double th[3], const double sn[3], const double cs[3], double det, double w[3]) {
  // One division for both 1 / (sin0 sin1 sin2) and 1 / det (divisions dominate this function's cost).
  const double sss = sn[0] * sn[1] * sn[2];
  const double r = 1.0 / (sss * det);
  const double inv_sss = det * r, inv_det = sss * r;
  const double a0 = (cs[0] - cs[1] * cs[2]) * sn[0] * inv_sss;
  const double a1 = (cs[1] - cs[2] * cs[0]) * sn[1] * inv_sss;
  const double a2 = (cs[2] - cs[0] * cs[1]) * sn[2] * inv_sss;
  w[0] = (th[0] - a1 * th[2] - a2 * th[1]) * sn[0] * inv_det;
  w[1] = (th[1] - a2 * th[0] - a0 * th[2]) * sn[1] * inv_det;
  w[2] = (th[2] - a0 * th[1] - a1 * th[0]) * sn[2] * inv_det;
}

// atan2(y, x) for y, x >= 0 (not both 0), to about 1 ulp: the Cephes Math Library's atan (S. L. Moshier,
// atan.c: range reduction to |t| <= 0.66 and a 4/5 rational approximation) with the division folded into
// the reduction. Inlined, it is ~3x faster than libm's atan2, which dominated the binding time; the
// accuracy was checked against std::atan2 in tests/cpp/basis/mean_value_coordinates_test.cpp.
inline double atan2_nonnegative(double y, double x) {
  constexpr double P0 = -8.750608600031904122785e-1, P1 = -1.615753718733365076637e1, P2 = -7.500855792314704667340e1,
                   P3 = -1.228866684490136173410e2, P4 = -6.485021904942025371773e1;
  constexpr double Q0 = 2.485846490142306297962e1, Q1 = 1.650270098316988542046e2, Q2 = 4.328810604912902668951e2,
                   Q3 = 4.853903996359136964868e2, Q4 = 1.945506571482613964425e2;
  constexpr double kMoreBits = 6.123233995736765886130e-17;  // pi/2 - double(pi/2)
  double base, extra, t;
  if (y > 2.41421356237309504880 * x) {  // angle > 3 pi / 8
    base = kPi / 2;
    extra = kMoreBits;
    t = -x / y;
  } else if (y <= 0.66 * x) {
    base = 0.0;
    extra = 0.0;
    t = y / x;
  } else {
    base = kPi / 4;
    extra = 0.5 * kMoreBits;
    t = (y - x) / (y + x);
  }
  const double z = t * t;
  const double p = (((P0 * z + P1) * z + P2) * z + P3) * z + P4;
  const double q = ((((z + Q0) * z + Q1) * z + Q2) * z + Q3) * z + Q4;
  return base + (t * (z * p / q) + t + extra);
}

}  // namespace

// Exposed for the test of its accuracy (not in the header: an implementation detail).
double mvc_atan2_nonnegative_for_test(double y, double x) { return atan2_nonnegative(y, x); }

CageData prepare_cage(const Mesh& cage, const std::string& what) {
  CageData data;
  data.m = static_cast<int>(cage.V.rows());
  const int f = static_cast<int>(cage.F.rows());
  if (data.m < 4 || f < 4)
    throw Error(ErrorCode::InvalidMesh, what + ": the cage needs at least 4 vertices and 4 triangles (has " +
                                            std::to_string(data.m) + " and " + std::to_string(f) + ")");
  if (!cage.V.allFinite()) throw Error(ErrorCode::InvalidMesh, what + ": the cage has non-finite coordinates");
  data.px.resize(data.m);
  data.py.resize(data.m);
  data.pz.resize(data.m);
  for (int j = 0; j < data.m; ++j) {
    data.px[j] = cage.V(j, 0);
    data.py[j] = cage.V(j, 1);
    data.pz[j] = cage.V(j, 2);
  }
  data.scale = std::max(bounding_box_diagonal(cage.V), std::numeric_limits<double>::min());
  std::unordered_map<long long, int> edge_id;
  auto edge = [&](int a, int b) {
    const long long key = static_cast<long long>(std::min(a, b)) * data.m + std::max(a, b);
    auto [it, inserted] = edge_id.emplace(key, static_cast<int>(data.edge_a.size()));
    if (inserted) {
      data.edge_a.push_back(a);
      data.edge_b.push_back(b);
    }
    return it->second;
  };
  data.tri.resize(3 * f);
  data.tri_edge.resize(3 * f);
  for (int t = 0; t < f; ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = cage.F(t, k);
      if (v < 0 || v >= data.m)
        throw Error(ErrorCode::InvalidMesh, what + ": cage triangle " + std::to_string(t) + " has vertex index " +
                                                std::to_string(v) + ", outside 0.." + std::to_string(data.m - 1));
      data.tri[3 * t + k] = v;
    }
    for (int k = 0; k < 3; ++k) data.tri_edge[3 * t + k] = edge(cage.F(t, (k + 1) % 3), cage.F(t, (k + 2) % 3));
  }
  return data;
}

MeanValueIntegrals::MeanValueIntegrals(const CageData& cage)
    : c_(cage),
      ux_(cage.m),
      uy_(cage.m),
      uz_(cage.m),
      d_(cage.m),
      acc_(cage.m),
      theta_(cage.edge_a.size()),
      cos_(cage.edge_a.size()),
      sin_(cage.edge_a.size()) {}

double MeanValueIntegrals::integrate(double x, double y, double z, double* row, PointKind& kind,
                                     std::vector<int>* back_faces) {
  const int m = c_.m;
  const double on_vertex = kOnVertex * c_.scale;
  if (back_faces) back_faces->clear();
  // Unit vectors u_j and distances d_j, once per point for all cage vertices.
  for (int j = 0; j < m; ++j) {
    const double vx = c_.px[j] - x, vy = c_.py[j] - y, vz = c_.pz[j] - z;
    const double d = std::sqrt(vx * vx + vy * vy + vz * vz);
    const double inv = 1.0 / d;
    ux_[j] = vx * inv;
    uy_[j] = vy * inv;
    uz_[j] = vz * inv;
    d_[j] = d;
  }
  for (int j = 0; j < m; ++j)
    if (d_[j] < on_vertex) {
      std::fill(row, row + m, 0.0);
      row[j] = 1.0;
      kind = PointKind::OnVertex;
      return 1.0;
    }
  // Arc length, cosine and sine of every cage edge seen from the point. With |a-b| = 2 sin(theta/2) and
  // |a+b| = 2 cos(theta/2), theta = 2 atan2(|a-b|, |a+b|) is accurate over the whole range [0, pi]
  // (2 asin(|a-b|/2) loses half the digits near pi, i.e. near an edge), and sin(theta) = |a-b||a+b|/2.
  const int edges = static_cast<int>(c_.edge_a.size());
  for (int e = 0; e < edges; ++e) {
    const int a = c_.edge_a[e], b = c_.edge_b[e];
    const double mx = ux_[a] - ux_[b], my = uy_[a] - uy_[b], mz = uz_[a] - uz_[b];
    const double sx = ux_[a] + ux_[b], sy = uy_[a] + uy_[b], sz = uz_[a] + uz_[b];
    const double lm = std::sqrt(mx * mx + my * my + mz * mz);
    const double lp = std::sqrt(sx * sx + sy * sy + sz * sz);
    theta_[e] = 2.0 * atan2_nonnegative(lm, lp);
    sin_[e] = 0.5 * lm * lp;
    cos_[e] = ux_[a] * ux_[b] + uy_[a] * uy_[b] + uz_[a] * uz_[b];
  }
  std::fill(acc_.begin(), acc_.end(), 0.0);
  double back_total = 0.0;  // the back-facing triangles' share of the total (positive coordinates only)
  const int faces = c_.faces();
  for (int t = 0; t < faces; ++t) {
    const int i0 = c_.tri[3 * t], i1 = c_.tri[3 * t + 1], i2 = c_.tri[3 * t + 2];
    const int e0 = c_.tri_edge[3 * t], e1 = c_.tri_edge[3 * t + 1], e2 = c_.tri_edge[3 * t + 2];
    // det[u0 u1 u2] > 0 when the point is on the inner side of an outward triangle.
    const double det = ux_[i0] * (uy_[i1] * uz_[i2] - uz_[i1] * uy_[i2]) +
                       uy_[i0] * (uz_[i1] * ux_[i2] - ux_[i1] * uz_[i2]) +
                       uz_[i0] * (ux_[i1] * uy_[i2] - uy_[i1] * ux_[i2]);
    const double th[3] = {theta_[e0], theta_[e1], theta_[e2]};
    const double sn[3] = {sin_[e0], sin_[e1], sin_[e2]};
    if (std::abs(det) < kThin) {
      const double h = 0.5 * (th[0] + th[1] + th[2]);
      if (kPi - h >= kOverTriangle) {  // near the triangle's plane, beside it
        // Its projection is a sliver of solid angle O(det): the positive coordinates drop the back-facing
        // ones (their occlusion is as small) and keep the front-facing ones, as mean value coordinates do.
        if (!back_faces || det >= 0) thin_triangle_weights(t, x, y, z);
        continue;
      }
      if (std::abs(det) < kOnFace) {
        // On the triangle: its barycentric coordinates (area opposite vertex k = d_{k+1} d_{k+2} sin th_k / 2).
        const double b0 = sn[0] * d_[i1] * d_[i2], b1 = sn[1] * d_[i2] * d_[i0], b2 = sn[2] * d_[i0] * d_[i1];
        const double total = b0 + b1 + b2;
        if (!(total > 0.0)) continue;  // a degenerate triangle; the point is also on a proper neighbour
        std::fill(row, row + m, 0.0);
        row[i0] += b0 / total;
        row[i1] += b1 / total;
        row[i2] += b2 / total;
        kind = PointKind::OnFace;
        return 1.0;
      }
    }
    const double cs[3] = {cos_[e0], cos_[e1], cos_[e2]};
    double w[3];
    triangle_weights(th, sn, cs, det, w);
    if (back_faces && det < 0) {
      back_faces->push_back(t);
      back_total += w[0] / d_[i0] + w[1] / d_[i1] + w[2] / d_[i2];
      continue;
    }
    acc_[i0] += w[0];  // the 1/d_k is applied once per vertex after the loop
    acc_[i1] += w[1];
    acc_[i2] += w[2];
  }
  // The formula above leaves out JSW's factor 1/2 (and 1/d_k): restored here, so row holds the integrals.
  double total = 0.5 * back_total;
  for (int j = 0; j < m; ++j) {
    row[j] = 0.5 * acc_[j] / d_[j];
    total += row[j];
  }
  kind = PointKind::Regular;
  return total;
}

// A triangle whose plane passes within |det| < kThin of the point, the point beside it. Its contribution
// C(t), as a function of the point's signed distance t to the plane, is t I(t) with I smooth and even
// (C = t * integral over the triangle of b_k(y) / |y|^4), so C(t) = (C(t + delta) + C(t - delta)) / 2
// + O(delta^2 t): evaluate the general formula at the point moved by +-delta along the normal, where
// |det| ~ 1e-5 is large enough for it to be accurate, and average. det = 2 t A / (d0 d1 d2) (A the
// triangle's area) gives the delta for that target; delta is capped at 1% of the distance to the
// triangle's vertices so the O(delta^2) term stays negligible. Zero-area triangles contribute nothing.
void MeanValueIntegrals::thin_triangle_weights(int t, double x, double y, double z) {
  const int* v = &c_.tri[3 * t];
  Eigen::Vector3d p[3], q = Eigen::Vector3d(x, y, z);
  for (int k = 0; k < 3; ++k) p[k] = Eigen::Vector3d(c_.px[v[k]], c_.py[v[k]], c_.pz[v[k]]);
  const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
  const double twice_area = normal.norm();
  const double d0 = d_[v[0]], d1 = d_[v[1]], d2 = d_[v[2]];
  if (!(twice_area > 1e-14 * std::max({d0, d1, d2}) * std::max({d0, d1, d2}))) return;
  const double delta = std::min(kThinTarget * d0 * d1 * d2 / twice_area, 1e-2 * std::min({d0, d1, d2}));
  const Eigen::Vector3d unit_normal = normal / twice_area;
  for (double side : {-1.0, 1.0}) {
    const Eigen::Vector3d moved = q + side * delta * unit_normal;
    Eigen::Vector3d u[3];
    double d[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d r = p[k] - moved;
      d[k] = r.norm();
      u[k] = r / d[k];
    }
    double th[3], sn[3], cs[3], w[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d& a = u[(k + 1) % 3];
      const Eigen::Vector3d& b = u[(k + 2) % 3];
      const double lm = (a - b).norm(), lp = (a + b).norm();
      th[k] = 2.0 * atan2_nonnegative(lm, lp);
      sn[k] = 0.5 * lm * lp;
      cs[k] = a.dot(b);
    }
    const double det = u[0].dot(u[1].cross(u[2]));
    if (det == 0.0) continue;
    triangle_weights(th, sn, cs, det, w);
    // acc_ is divided by the unmoved point's d_k after the loop.
    for (int k = 0; k < 3; ++k) acc_[v[k]] += 0.5 * w[k] / d[k] * d_[v[k]];
  }
}

}  // namespace sd
