#include "core/solver/internal/reduced/training_poses.h"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>

#include "core/mesh/volume.h"

namespace sd {

double PortableRandom::uniform() {
  // SplitMix64: a fixed integer recipe, so the numbers do not depend on the standard library.
  state_ += 0x9E3779B97F4A7C15ull;
  unsigned long long z = state_;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0);
}

double PortableRandom::gaussian() {
  const double u = std::max(uniform(), 1e-300), v = uniform();
  return std::sqrt(-2.0 * std::log(u)) * std::cos(6.283185307179586 * v);
}

Eigen::Vector3d PortableRandom::direction() {
  const double z = uniform(-1.0, 1.0), phi = uniform(0.0, 6.283185307179586), r = std::sqrt(1.0 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

namespace {

using Field = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;

double smoothstep(double a, double b, double x) {
  const double t = std::clamp((x - a) / (b - a), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Eigen::Vector3d perpendicular(const Eigen::Vector3d& e, PortableRandom& random) {
  Eigen::Vector3d a = e.cross(random.direction());
  while (a.norm() < 1e-3) a = e.cross(random.direction());
  return a.normalized();
}

// The families of smooth deformations, about the centre c of a model of diagonal D.
struct Families {
  Eigen::Vector3d c;
  double D;

  // Rotation by up to `angle` about an axis a through c; the turned part is the half s = (x - c).e > 0, blended
  // over a hinge band of width 0.3 D around c.
  Field bend(const Eigen::Vector3d& e, const Eigen::Vector3d& a, double angle) const {
    return [=, *this](const Eigen::Vector3d& x) {
      const double s = (x - c).dot(e) / D;
      const Eigen::AngleAxisd turn(angle * smoothstep(-0.15, 0.15, s), a);
      return Eigen::Vector3d(c + turn * (x - c));
    };
  }
  // Rotation about the axis e through c by an angle growing linearly along e.
  Field twist(const Eigen::Vector3d& e, double angle) const {
    return [=, *this](const Eigen::Vector3d& x) {
      const Eigen::AngleAxisd turn(angle * (x - c).dot(e) / D, e);
      return Eigen::Vector3d(c + turn * (x - c));
    };
  }
  // A Gaussian bump of the given amplitude along n, of radius 0.25 D, centred at p.
  Field bump(const Eigen::Vector3d& p, const Eigen::Vector3d& n, double amplitude) const {
    return [=, *this](const Eigen::Vector3d& x) {
      const double r2 = (x - p).squaredNorm() / (0.0625 * D * D);
      return Eigen::Vector3d(x + amplitude * std::exp(-r2) * n);
    };
  }
  // Scaling by `factor` along e.
  Field stretch(const Eigen::Vector3d& e, double factor) const {
    return [=, *this](const Eigen::Vector3d& x) { return Eigen::Vector3d(x + (factor - 1.0) * (x - c).dot(e) * e); };
  }
  // Scaling across e by 1 + k s, s the position along e.
  Field taper(const Eigen::Vector3d& e, double k) const {
    return [=, *this](const Eigen::Vector3d& x) {
      const Eigen::Vector3d d = x - c;
      const double s = d.dot(e) / D;
      const Eigen::Vector3d across = d - d.dot(e) * e;
      return Eigen::Vector3d(c + d.dot(e) * e + (1.0 + k * s) * across);
    };
  }
};

double signed_angle(PortableRandom& random, double lo, double hi) {
  const double a = random.uniform(lo, hi) * 3.141592653589793 / 180.0;
  return random.uniform() < 0.5 ? -a : a;
}

// Pose t cycles through the families; every fifth combines a bend with a bump.
Field random_field(int t, const Families& f, const Vertices& X0, PortableRandom& random) {
  const Eigen::Vector3d e = random.direction();
  switch (t % 5) {
    case 0: return f.bend(e, perpendicular(e, random), signed_angle(random, 15, 90));
    case 1: return f.twist(e, signed_angle(random, 15, 90));
    case 2: {
      const Eigen::Vector3d p = X0.row(random.below(static_cast<int>(X0.rows()))).transpose();
      return f.bump(p, random.direction(), random.uniform(0.03, 0.15) * f.D);
    }
    case 3:
      return random.uniform() < 0.5 ? f.stretch(e, random.uniform(0.7, 1.4)) : f.taper(e, random.uniform(-0.6, 0.6));
    default: {
      const Field bend = f.bend(e, perpendicular(e, random), signed_angle(random, 15, 60));
      const Eigen::Vector3d p = X0.row(random.below(static_cast<int>(X0.rows()))).transpose();
      const Field bump = f.bump(p, random.direction(), random.uniform(0.03, 0.1) * f.D);
      return [bend, bump](const Eigen::Vector3d& x) { return bend(bump(x)); };
    }
  }
}

}  // namespace

std::vector<Eigen::MatrixXd> training_poses(const Vertices& X0, const BasisMatrix& W, const Eigen::MatrixXd& U0,
                                            int count, unsigned seed) {
  PortableRandom random(seed);
  const int n = static_cast<int>(X0.rows()), m = W.cols();
  // The fit's rows: every vertex on small meshes, else a random subset of at least 4 per unknown.
  std::vector<int> rows;
  const int fit_rows = std::min(n, std::max(4000, 4 * m));
  if (fit_rows == n) {
    for (int i = 0; i < n; ++i) rows.push_back(i);
  } else {
    for (int k = 0; k < fit_rows; ++k) rows.push_back(random.below(n));
  }
  const Eigen::MatrixXd WR = W.select_rows(rows).to_dense();
  // Least squares with a small Tikhonov term: motions of the unknowns the rows barely see stay put.
  Eigen::MatrixXd G = WR.transpose() * WR;
  G.diagonal().array() += 1e-8 * G.diagonal().mean();
  const Eigen::LDLT<Eigen::MatrixXd> fit(G);

  const Eigen::Vector3d lo = X0.colwise().minCoeff().transpose(), hi = X0.colwise().maxCoeff().transpose();
  const Families families{0.5 * (lo + hi), bounding_box_diagonal(X0)};
  std::vector<Eigen::MatrixXd> poses;
  for (int t = 0; t < count; ++t) {
    const Field field = random_field(t, families, X0, random);
    Eigen::MatrixXd displacement(rows.size(), 3);
    for (size_t r = 0; r < rows.size(); ++r) {
      const Eigen::Vector3d x = X0.row(rows[r]).transpose();
      displacement.row(static_cast<Eigen::Index>(r)) = (field(x) - x).transpose();
    }
    poses.push_back(U0 + fit.solve(WR.transpose() * displacement));
  }
  return poses;
}

}  // namespace sd
