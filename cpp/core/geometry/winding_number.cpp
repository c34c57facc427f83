#include "core/geometry/winding_number.h"

#include <cmath>

namespace sd {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A point in the plane of a triangle (|det| below this times |a||b||c|) sees it edge-on: its solid
// angle jumps from -2 pi to 2 pi across the interior, and counting 0 there gives the mean, so a point
// on a face of a closed mesh has winding number 1/2.
constexpr double kCoplanar = 1e-14;

// Half the solid angle of triangle (a, b, c) seen from the origin, van Oosterom and Strackee (1983):
// tan(omega / 2) = det[a b c] / (|a||b||c| + (a.b)|c| + (b.c)|a| + (c.a)|b|).
inline double half_solid_angle(double det, double den, double la, double lb, double lc) {
  if (std::abs(det) <= kCoplanar * la * lb * lc) return 0.0;
  return std::atan2(det, den);
}

inline double solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
  return 2.0 * half_solid_angle(det, den, la, lb, lc);
}

// Faces are processed in blocks of this many so that the ~20 work arrays stay in the L1 cache.
constexpr Eigen::Index kBlock = 128;

}  // namespace

double winding_number(const Mesh& mesh, const Eigen::RowVector3d& p) {
  double sum = 0;
  for (int f = 0; f < mesh.F.rows(); ++f)
    sum += solid_angle((mesh.V.row(mesh.F(f, 0)) - p).transpose(), (mesh.V.row(mesh.F(f, 1)) - p).transpose(),
                       (mesh.V.row(mesh.F(f, 2)) - p).transpose());
  return sum / (4.0 * kPi);
}

// The mesh in structure-of-arrays form so the per-point work over its faces runs as Eigen array
// expressions (SIMD sqrt, division and selects; a plain loop does not vectorise because std::sqrt may
// set errno and std::atan2 is a library call).
struct BatchWindingNumber::Impl {
  Eigen::ArrayXd ax, ay, az, bx, by, bz, cx, cy, cz;  // corners, padded to whole blocks
};

// One caller's per-face work arrays: corners relative to the point, their lengths, and the atan2 terms.
struct BatchWindingNumber::Scratch::Impl {
  Eigen::ArrayXd rax, ray, raz, rbx, rby, rbz, rcx, rcy, rcz, la, lb, lc, y, x, a, t, z, series, r;
  Eigen::Array<bool, Eigen::Dynamic, 1> reduce;

  // atan2(y, x) element-wise without branches, summed. Reduce to t in [-tan(pi/8), tan(pi/8)] (octant
  // symmetry, then atan(a) = pi/4 + atan((a - 1) / (a + 1))) and sum the Taylor series to t^21: the
  // remainder is below 0.4143^23 / 23 < 2e-10 rad per face (measured 6e-11), far below what the 1/2
  // threshold needs.
  double sum_atan2() {
    a = (x.abs().max(y.abs()) > 0).select(x.abs().min(y.abs()) / x.abs().max(y.abs()), 0.0);
    reduce = a > 0.41421356237309503;
    t = reduce.select((a - 1.0) / (a + 1.0), a);
    z = t.square();
    series.setConstant(t.size(), 1.0 / 21);  // atan(t) / t = sum_j (-1)^j z^j / (2j + 1), Horner
    for (int j = 9; j >= 0; --j) series = (j % 2 ? -1.0 : 1.0) / (2 * j + 1) + z * series;
    r = t * series + reduce.select(Eigen::ArrayXd::Constant(t.size(), kPi / 4), 0.0);
    r = (y.abs() > x.abs()).select(kPi / 2 - r, r);
    r = (x < 0).select(kPi - r, r);
    return (y < 0).select(-r, r).sum();
  }

  // Sum of half solid angles for the block of faces whose corners relative to the point are in r*.
  double block_half_angles() {
    la = (rax.square() + ray.square() + raz.square()).sqrt();
    lb = (rbx.square() + rby.square() + rbz.square()).sqrt();
    lc = (rcx.square() + rcy.square() + rcz.square()).sqrt();
    y = rax * (rby * rcz - rbz * rcy) + ray * (rbz * rcx - rbx * rcz) + raz * (rbx * rcy - rby * rcx);
    x = la * lb * lc + (rax * rbx + ray * rby + raz * rbz) * lc + (rbx * rcx + rby * rcy + rbz * rcz) * la +
        (rcx * rax + rcy * ray + rcz * raz) * lb;
    // Coplanar faces contribute atan2(0, 1) = 0 (see kCoplanar).
    reduce = y.abs() <= kCoplanar * la * lb * lc;
    y = reduce.select(0.0, y);
    x = reduce.select(1.0, x);
    return sum_atan2();
  }
};

BatchWindingNumber::Scratch::Scratch() : impl_(std::make_unique<Impl>()) {}
BatchWindingNumber::Scratch::~Scratch() = default;

BatchWindingNumber::BatchWindingNumber(const Mesh& mesh) : impl_(std::make_unique<Impl>()) {
  Impl& c = *impl_;
  const Eigen::Index n = mesh.F.rows();
  // The last block is padded with point triangles at the first vertex of the first face: their det is
  // exactly 0, so they count as coplanar and add nothing.
  const Eigen::Index padded = (n + kBlock - 1) / kBlock * kBlock;
  const Eigen::RowVector3d pad = mesh.V.row(mesh.F(0, 0));
  c.ax.setConstant(padded, pad.x()), c.ay.setConstant(padded, pad.y()), c.az.setConstant(padded, pad.z());
  c.bx = c.ax, c.by = c.ay, c.bz = c.az, c.cx = c.ax, c.cy = c.ay, c.cz = c.az;
  for (Eigen::Index f = 0; f < n; ++f) {
    const Eigen::RowVector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), d = mesh.V.row(mesh.F(f, 2));
    c.ax[f] = a.x(), c.ay[f] = a.y(), c.az[f] = a.z();
    c.bx[f] = b.x(), c.by[f] = b.y(), c.bz[f] = b.z();
    c.cx[f] = d.x(), c.cy[f] = d.y(), c.cz[f] = d.z();
  }
}

BatchWindingNumber::~BatchWindingNumber() = default;

double BatchWindingNumber::operator()(const Eigen::RowVector3d& p, Scratch& scratch) const {
  const Impl& c = *impl_;
  Scratch::Impl& s = *scratch.impl_;
  double sum = 0;
  for (Eigen::Index b = 0; b < c.ax.size(); b += kBlock) {
    s.rax = c.ax.segment(b, kBlock) - p.x(), s.ray = c.ay.segment(b, kBlock) - p.y();
    s.raz = c.az.segment(b, kBlock) - p.z(), s.rbx = c.bx.segment(b, kBlock) - p.x();
    s.rby = c.by.segment(b, kBlock) - p.y(), s.rbz = c.bz.segment(b, kBlock) - p.z();
    s.rcx = c.cx.segment(b, kBlock) - p.x(), s.rcy = c.cy.segment(b, kBlock) - p.y();
    s.rcz = c.cz.segment(b, kBlock) - p.z();
    sum += s.block_half_angles();
  }
  return sum / (2.0 * kPi);  // sum of omega / 2 over faces / (2 pi) = sum omega / (4 pi)
}

}  // namespace sd
