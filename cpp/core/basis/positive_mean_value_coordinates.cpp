#include "core/basis/positive_mean_value_coordinates.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/geometry/ray_caster.h"
#include "core/timer.h"
#include "core/basis/internal/mean_value_integrals.h"
#include "core/basis/internal/row_binding.h"

namespace sd {
namespace {

constexpr const char* kWhat = "positive mean value coordinates";
constexpr double kPi = 3.14159265358979323846;
// A back-facing triangle is cut into at most this many cells per side (a point very close to a large one).
constexpr int kMaxCellsPerSide = 96;

// Solid angle of the spherical triangle of unit vectors a, b, c (Van Oosterom and Strackee 1983).
double solid_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double det = a.dot(b.cross(c));
  return 2.0 * std::atan2(std::abs(det), 1.0 + a.dot(b) + b.dot(c) + c.dot(a));
}

// The angle between unit vectors a and b, accurate over [0, pi].
double arc(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return 2.0 * std::atan2((a - b).norm(), (a + b).norm());
}

class PositiveMeanValueRow : public RowEvaluator {
 public:
  PositiveMeanValueRow(const CageData& data, const Mesh& cage, const RayCaster& caster, const Vertices& points,
                       double cell_solid_angle)
      : data_(data),
        cage_(cage),
        caster_(caster),
        points_(points),
        cell_(cell_solid_angle),
        integrals_(data),
        mean_(data.faces()),
        touched_(data.faces(), 0) {}

  bool evaluate(int i, double* row, PointKind& kind) override {
    const Eigen::Vector3d x = points_.row(i).transpose();
    const double total = integrals_.integrate(x[0], x[1], x[2], row, kind, &back_);
    if (!(total > 0.0)) return false;
    if (kind != PointKind::Regular) return true;  // on the cage: the delta or barycentric row, as for MVC
    for (int b : back_) subtract_hidden(b, x);
    subtract_hidden_parts(x, row);
    stats.hidden_faces += static_cast<double>(back_.size());
    // The visible integral of 1/r is positive, so the row keeps a positive sum; entries below 0 are
    // sampling error (a cell given wholly to a triangle that covers only part of it).
    double sum = 0.0, negative = 0.0;
    for (int j = 0; j < data_.m; ++j) {
      sum += row[j];
      if (row[j] < 0.0) {
        negative -= row[j];
        stats.clamped += 1;
        row[j] = 0.0;
      }
    }
    const double kept = sum + negative;
    const double inv = 1.0 / kept;
    for (int j = 0; j < data_.m; ++j) row[j] *= inv;
    stats.clamped_mass += negative * inv;
    return true;
  }

  std::vector<double> tallies() const override {
    return {stats.rays, stats.hidden_faces, stats.clamped, stats.clamped_mass};
  }

  PositiveMvcReport stats;

 private:
  // Adds to hidden_ what the front-facing triangles behind back-facing triangle b would contribute over b's
  // projection. b is cut into s x s cells (s from its solid angle), in "up" cells (a, c) with corners
  // (a, c), (a + 1, c), (a, c + 1) of the grid p0 + a e1 + c e2, a + c < s, and "down" cells (a, c) with
  // corners (a + 1, c), (a + 1, c + 1), (a, c + 1), a + c < s - 1; one ray per cell finds the triangle behind.
  void subtract_hidden(int b, const Eigen::Vector3d& x) {
    const int* v = &data_.tri[3 * b];
    const Eigen::Vector3d p[3] = {corner(v[0]), corner(v[1]), corner(v[2])};
    const double omega =
        solid_angle(integrals_.direction(v[0]), integrals_.direction(v[1]), integrals_.direction(v[2]));
    const int s = std::clamp(static_cast<int>(std::ceil(std::sqrt(omega / cell_))), 1, kMaxCellsPerSide);
    const Eigen::Vector3d e1 = (p[1] - p[0]) / s, e2 = (p[2] - p[0]) / s;
    // Unit directions from x to the grid points, and the triangle behind each cell.
    directions_.resize((s + 1) * (s + 1));
    for (int a = 0; a <= s; ++a)
      for (int c = 0; a + c <= s; ++c) directions_[a * (s + 1) + c] = (p[0] + a * e1 + c * e2 - x).normalized();
    up_.assign(s * s, -1);
    down_.assign(s * s, -1);
    const bool gathered = s > 1;  // a lone cell: one ray through the tree instead
    if (gathered) gather_candidates(b, x, p);
    for (int a = 0; a < s; ++a)
      for (int c = 0; a + c < s; ++c) {
        const Eigen::Vector3d up_centre = p[0] + (a + 1.0 / 3) * e1 + (c + 1.0 / 3) * e2;
        up_[a * s + c] = behind(b, x, up_centre, gathered);
        if (a + c + 2 <= s) down_[a * s + c] = behind(b, x, p[0] + (a + 2.0 / 3) * e1 + (c + 2.0 / 3) * e2, gathered);
      }
    // Each up cell's edges with the cell across them: a down cell, or nothing on b's outline. Cells behind the
    // same triangle cancel along their shared edge.
    auto grid = [&](int a, int c) -> const Eigen::Vector3d& { return directions_[a * (s + 1) + c]; };
    for (int a = 0; a < s; ++a)
      for (int c = 0; a + c < s; ++c) {
        const int face = up_[a * s + c];
        edge(grid(a, c), grid(a + 1, c), face, c > 0 ? down_[a * s + c - 1] : -1);
        edge(grid(a + 1, c), grid(a, c + 1), face, a + c + 2 <= s ? down_[a * s + c] : -1);
        edge(grid(a, c + 1), grid(a, c), face, a > 0 ? down_[(a - 1) * s + c] : -1);
      }
  }

  // The directed edge from -> to (unit directions) of a cell behind triangle `face`; `across` is the triangle
  // behind the cell on its other side (-1: none). A cell's mean vector, the integral of the direction over its
  // projection, is -1/2 sum over its edges of arc x unit normal of the great circle (minus: b's cells turn
  // clockwise seen from x); the neighbour runs the edge the other way.
  void edge(const Eigen::Vector3d& from, const Eigen::Vector3d& to, int face, int across) {
    if (face == across) return;
    const Eigen::Vector3d normal = from.cross(to);
    const double length = normal.norm();
    if (length == 0.0) return;
    const Eigen::Vector3d share = (-0.5 * arc(from, to) / length) * normal;
    if (face >= 0) hidden_mean(face) += share;
    if (across >= 0) hidden_mean(across) -= share;
  }

  // The triangle behind back-facing triangle b on the ray from x through `through` (a point on b): the first
  // crossing beyond b; -1 when none (only possible through rounding at a cage edge).
  int behind(int b, const Eigen::Vector3d& x, const Eigen::Vector3d& through, bool gathered) {
    const Eigen::Vector3d ray = through - x;
    stats.rays += 1;
    if (!gathered) return caster_.first_hit(through, ray, 1e-12, std::numeric_limits<double>::infinity(), b).face;
    // The hit's depth beyond b's plane grows along the ray: a candidate whose every point is deeper than the
    // best hit so far cannot be nearer.
    RayHit hit;
    double t_best = std::numeric_limits<double>::infinity(), depth_best = t_best;
    const double start = (through - origin_).dot(inward_), rate = ray.dot(inward_);
    int face = -1;
    for (const auto& [depth, f] : candidates_) {
      if (depth >= depth_best) break;
      if (!caster_.intersect(f, through, ray, 1e-12, t_best, hit)) continue;
      t_best = hit.t;
      depth_best = start + t_best * rate;
      face = f;
    }
    return face;
  }

  // candidates_ = the front-facing triangles (x on their inner side) that may meet the pyramid from x through
  // back-facing triangle b, beyond b (bounded by its three sides through x and b's edges, and by b's plane),
  // sorted by their smallest depth beyond b's plane.
  void gather_candidates(int b, const Eigen::Vector3d& x, const Eigen::Vector3d p[3]) {
    region_.clear();
    for (int k = 0; k < 3; ++k) {
      Eigen::Vector3d normal = (p[k] - x).cross(p[(k + 1) % 3] - x);
      if (normal.dot(p[(k + 2) % 3] - x) < 0) normal = -normal;
      region_.push_back({normal, normal.dot(x)});
    }
    // b is outward and x is on its outer side: beyond b is along its inward normal.
    inward_ = (p[2] - p[0]).cross(p[1] - p[0]).normalized();
    origin_ = p[0];
    region_.push_back({inward_, inward_.dot(p[0])});
    // A little slack: a triangle touching the region only along an edge is harmless, one lost to rounding is not.
    for (RayCaster::HalfSpace& h : region_) h.offset -= 1e-9 * h.normal.norm() * data_.scale;
    boxed_.clear();
    caster_.faces_in_region(region_, boxed_);
    candidates_.clear();
    for (int f : boxed_) {
      if (f == b) continue;
      const int* t = &data_.tri[3 * f];
      const Eigen::Vector3d q[3] = {corner(t[0]), corner(t[1]), corner(t[2])};
      if ((q[1] - q[0]).cross(q[2] - q[0]).dot(q[0] - x) <= 0) continue;  // x not on its inner side
      bool outside = false;
      for (const RayCaster::HalfSpace& h : region_)
        outside = outside ||
                  (h.normal.dot(q[0]) < h.offset && h.normal.dot(q[1]) < h.offset && h.normal.dot(q[2]) < h.offset);
      if (outside) continue;
      const double depth =
          std::min({(q[0] - p[0]).dot(inward_), (q[1] - p[0]).dot(inward_), (q[2] - p[0]).dot(inward_)});
      candidates_.push_back({depth, f});
    }
    std::sort(candidates_.begin(), candidates_.end());
  }

  // The accumulated mean vector of the parts of triangle `face` hidden from the current point.
  Eigen::Vector3d& hidden_mean(int face) {
    if (!touched_[face]) {
      touched_[face] = 1;
      hidden_faces_.push_back(face);
      mean_[face].setZero();
    }
    return mean_[face];
  }

  // row -= what the hidden parts contributed: for each triangle, its hat functions' integrals over its hidden
  // part c solve sum_k c_k (p_k - x) = m (m its hidden mean vector), linear in m, so one solve per triangle.
  void subtract_hidden_parts(const Eigen::Vector3d& x, double* row) {
    for (int face : hidden_faces_) {
      touched_[face] = 0;
      const int* t = &data_.tri[3 * face];
      Eigen::Matrix3d M;
      for (int k = 0; k < 3; ++k) M.col(k) = corner(t[k]) - x;
      // The triangle faces x (a ray leaves the cage behind an entry); a grazing one is left out.
      const double scale = M.col(0).norm() * M.col(1).norm() * M.col(2).norm();
      if (!(M.determinant() > 1e-9 * scale)) continue;
      const Eigen::Vector3d c = M.inverse() * mean_[face];
      for (int k = 0; k < 3; ++k) row[t[k]] -= c[k];
    }
    hidden_faces_.clear();
  }

  Eigen::Vector3d corner(int j) const { return cage_.V.row(j).transpose(); }

  const CageData& data_;
  const Mesh& cage_;
  const RayCaster& caster_;
  const Vertices& points_;
  double cell_;  // the largest solid angle of a cell
  MeanValueIntegrals integrals_;
  std::vector<int> back_;  // the back-facing triangles of the current point
  // Per triangle (touched_, in the order hidden_faces_) the mean vector of its hidden part for this point.
  std::vector<Eigen::Vector3d> mean_;
  std::vector<char> touched_;
  std::vector<int> hidden_faces_;
  // The current back-facing triangle's grid directions and the triangle behind each cell.
  std::vector<Eigen::Vector3d> directions_;
  std::vector<int> up_, down_;
  // The current back-facing triangle's pyramid, its inward normal and a point of its plane, and the candidate
  // triangles behind it as (smallest depth beyond its plane, triangle).
  std::vector<RayCaster::HalfSpace> region_;
  Eigen::Vector3d inward_, origin_;
  std::vector<int> boxed_;
  std::vector<std::pair<double, int>> candidates_;
};

}  // namespace

BasisMatrix positive_mean_value_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                                            const PositiveMvcOptions& options, MvcReport* report,
                                            PositiveMvcReport* sampling) {
  const Timer timer;
  if (options.resolution < PositiveMvcOptions::kMinResolution ||
      options.resolution > PositiveMvcOptions::kMaxResolution)
    throw Error(std::string(kWhat) + ": the resolution must be an integer from " +
                std::to_string(PositiveMvcOptions::kMinResolution) + " to " +
                std::to_string(PositiveMvcOptions::kMaxResolution) + " (got " + std::to_string(options.resolution) +
                ")");
  const CageData data = prepare_cage(cage, kWhat);
  const int n = static_cast<int>(points.rows());
  check_weights_budget(n, data.m, binding);
  check_points_finite(points, kWhat);
  const RayCaster caster(cage);
  const double cell = 4.0 * kPi / (6.0 * options.resolution * options.resolution);
  MvcReport local;
  std::vector<double> tallies;
  BasisMatrix W = bind_rows(
      points, data.m, binding, kWhat,
      [&]() -> std::unique_ptr<RowEvaluator> {
        return std::make_unique<PositiveMeanValueRow>(data, cage, caster, points, cell);
      },
      local, &tallies);
  tallies.resize(4, 0.0);
  if (sampling) *sampling = PositiveMvcReport{tallies[0], tallies[1], tallies[2], tallies[3]};
  local.evaluations = double(n) * double(data.faces());
  local.seconds = timer.ms() / 1e3;
  if (report) *report = local;
  return W;
}

}  // namespace sd
