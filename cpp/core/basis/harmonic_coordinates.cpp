#include "core/basis/harmonic_coordinates.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "core/error.h"
#include "core/geometry/aabb_tree.h"
#include "core/geometry/point_triangle_distance.h"
#include "core/geometry/ray_caster.h"
#include "core/mesh/volume.h"
#include "core/parallel/parallel_for.h"
#include "core/timer.h"
#include "core/basis/internal/block_ldlt.h"
#include "core/basis/internal/cage_grid.h"
#include "core/basis/internal/mean_value_integrals.h"
#include "core/basis/internal/row_binding.h"

namespace sd {
namespace {

constexpr const char* kWhat = "harmonic coordinates";
// An arm shorter than this fraction of h is taken as this long (a node almost on the cage): the node's value
// is then the crossing's to within that fraction, and the matrix stays well conditioned.
constexpr double kShortestArm = 1e-3;
// Right-hand sides solved together: one stream over the factor per block.
constexpr int kBlockColumns = 16;

std::string megabytes(double bytes) {
  std::ostringstream out;
  out.precision(bytes < 10e6 ? 2 : 0);
  out << std::fixed << bytes / 1e6 << " MB";
  return out.str();
}

// A sparse row of values per cage vertex: a boundary value (a crossing's barycentric coordinates) or a mix of them.
using CageValues = std::vector<std::pair<int, double>>;

CageValues crossing_values(const Mesh& cage, const GridCrossing& c) {
  return {{cage.F(c.face, 0), c.bary[0]}, {cage.F(c.face, 1), c.bary[1]}, {cage.F(c.face, 2), c.bary[2]}};
}

// The grid, which nodes are unknowns, and the equations: A (lower triangle) and the boundary terms R.
struct GridSystem {
  std::vector<int> unknown;              // per grid node: its unknown, or -1 outside the cage
  std::vector<Eigen::Vector3i> node_of;  // per unknown: its grid indices
  Eigen::SparseMatrix<double> A;         // unknowns x unknowns, lower triangle
  Eigen::SparseMatrix<double> R;         // unknowns x cage vertices
};

const int kSteps[6][2] = {{0, 1}, {0, -1}, {1, 1}, {1, -1}, {2, 1}, {2, -1}};  // (axis, step) of the 6 arms

Eigen::Vector3i neighbour(const Eigen::Vector3i& at, int axis, int step) {
  Eigen::Vector3i next = at;
  next[axis] += step;
  return next;
}

bool in_grid(const CageGrid& grid, const Eigen::Vector3i& at) {
  return (at.array() >= 0).all() && (at.array() < grid.counts()).all();
}

// The cage's value at its nearest point to p (the barycentric coordinates of that point in its triangle).
CageValues nearest_cage_values(const Mesh& cage, const AabbTree& tree, const Eigen::Vector3d& p) {
  int best_face = -1;
  double best = std::numeric_limits<double>::infinity();
  tree.minimum([&](const Box3& box) { return box.squaredExteriorDistance(p); },
               [&](int f) {
                 const double d = point_triangle_squared_distance(p, cage.V.row(cage.F(f, 0)).transpose(),
                                                                  cage.V.row(cage.F(f, 1)).transpose(),
                                                                  cage.V.row(cage.F(f, 2)).transpose());
                 if (d < best) {
                   best = d;
                   best_face = f;
                 }
                 return d;
               });
  const Eigen::Vector3d a = cage.V.row(cage.F(best_face, 0)), b = cage.V.row(cage.F(best_face, 1)),
                        c = cage.V.row(cage.F(best_face, 2));
  // Barycentric coordinates of p's projection, clamped to the triangle (the nearest point lies in it).
  const Eigen::Vector3d n = (b - a).cross(c - a);
  double w[3] = {(c - b).cross(p - b).dot(n), (a - c).cross(p - c).dot(n), (b - a).cross(p - a).dot(n)};
  double total = 0;
  for (double& x : w) total += (x = std::max(0.0, x));
  if (!(total > 0)) return {{cage.F(best_face, 0), 1.0}};
  return {
      {cage.F(best_face, 0), w[0] / total}, {cage.F(best_face, 1), w[1] / total}, {cage.F(best_face, 2), w[2] / total}};
}

GridSystem assemble(const CageGrid& grid, const Mesh& cage, const AabbTree& tree) {
  GridSystem system;
  const Eigen::Array3i n = grid.counts();
  system.unknown.assign(static_cast<size_t>(n[0]) * n[1] * n[2], -1);
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const long long id = grid.node(i, j, k);
        if (!grid.inside(id)) continue;
        system.unknown[static_cast<size_t>(id)] = static_cast<int>(system.node_of.size());
        system.node_of.emplace_back(i, j, k);
      }
  const int unknowns = static_cast<int>(system.node_of.size());
  std::vector<Eigen::Triplet<double>> a, r;
  a.reserve(static_cast<size_t>(unknowns) * 4);
  std::vector<const GridCrossing*> between;
  for (int u = 0; u < unknowns; ++u) {
    const Eigen::Vector3i at = system.node_of[u];
    double diagonal = 0;
    for (const auto& [axis, step] : kSteps) {
      const Eigen::Vector3i next = neighbour(at, axis, step);
      grid.crossings_between(axis, at[0], at[1], at[2], step, between);
      const int v =
          in_grid(grid, next) ? system.unknown[static_cast<size_t>(grid.node(next[0], next[1], next[2]))] : -1;
      if (between.empty() && v >= 0) {  // an arm to another unknown
        diagonal += 1;
        if (v < u) a.emplace_back(u, v, -1.0);
        continue;
      }
      // An arm to the cage: where it first crosses; a neighbour outside without a crossing between (the two
      // lines' rounding disagreeing at a grazing crossing) takes the cage's value nearest to it.
      double alpha = 1;
      CageValues values;
      if (!between.empty()) {
        const int index[3] = {at[0], at[1], at[2]};
        alpha = std::abs(between.front()->at - (grid.origin()[axis] + grid.spacing() * index[axis])) / grid.spacing();
        values = crossing_values(cage, *between.front());
      } else {
        values = nearest_cage_values(cage, tree, grid.position(next[0], next[1], next[2]));
      }
      alpha = std::max(alpha, kShortestArm);
      diagonal += 1 / alpha;
      for (const auto& [vertex, value] : values) r.emplace_back(u, vertex, value / alpha);
    }
    a.emplace_back(u, u, diagonal);
  }
  system.A.resize(unknowns, unknowns);
  system.A.setFromTriplets(a.begin(), a.end());
  system.R.resize(unknowns, cage.V.rows());
  system.R.setFromTriplets(r.begin(), r.end());
  return system;
}

// How each point is interpolated: trilinear weights on its cell's corners, the corners inside as unknowns
// (`inner`, n x unknowns) and the values of those outside folded into `outer` (n x cage vertices).
struct Interpolation {
  Eigen::SparseMatrix<double, Eigen::RowMajor> inner;
  Eigen::SparseMatrix<double, Eigen::RowMajor> outer;
  int boundary_cells = 0;
  int unresolved = 0;
};

// A corner outside the cage: the boundary value where an arm from an inside neighbour leaves the cage (the
// average over such neighbours), else the value at the cage's nearest point.
CageValues outside_corner(const CageGrid& grid, const GridSystem& system, const Mesh& cage, const AabbTree& tree,
                          const Eigen::Vector3i& corner) {
  CageValues values;
  int arms = 0;
  std::vector<const GridCrossing*> between;
  for (const auto& [axis, step] : kSteps) {
    const Eigen::Vector3i from = neighbour(corner, axis, step);
    if (!in_grid(grid, from) || system.unknown[static_cast<size_t>(grid.node(from[0], from[1], from[2]))] < 0) continue;
    grid.crossings_between(axis, from[0], from[1], from[2], -step, between);
    if (between.empty()) continue;
    for (const auto& entry : crossing_values(cage, *between.front())) values.push_back(entry);
    ++arms;
  }
  if (arms == 0) return nearest_cage_values(cage, tree, grid.position(corner[0], corner[1], corner[2]));
  for (auto& entry : values) entry.second /= arms;
  return values;
}

Interpolation interpolation(const Vertices& points, const CageGrid& grid, const GridSystem& system, const Mesh& cage,
                            const AabbTree& tree) {
  const int n = static_cast<int>(points.rows());
  std::vector<Eigen::Triplet<double>> inner, outer;
  inner.reserve(static_cast<size_t>(n) * 8);
  std::unordered_map<long long, CageValues> outside;  // the outside corners met so far
  Interpolation result;
  for (int p = 0; p < n; ++p) {
    const Eigen::Vector3d local = (points.row(p).transpose() - grid.origin()) / grid.spacing();
    Eigen::Vector3i cell;
    Eigen::Vector3d t;
    for (int a = 0; a < 3; ++a) {
      cell[a] = std::clamp(static_cast<int>(std::floor(local[a])), 0, grid.counts()[a] - 2);
      t[a] = std::clamp(local[a] - cell[a], 0.0, 1.0);
    }
    int inside_corners = 0;
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3i corner = cell + Eigen::Vector3i(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      const double weight = (c & 1 ? t[0] : 1 - t[0]) * (c & 2 ? t[1] : 1 - t[1]) * (c & 4 ? t[2] : 1 - t[2]);
      const long long id = grid.node(corner[0], corner[1], corner[2]);
      const int u = system.unknown[static_cast<size_t>(id)];
      if (u >= 0) {
        ++inside_corners;
        if (weight != 0) inner.emplace_back(p, u, weight);
        continue;
      }
      if (weight == 0) continue;
      auto found = outside.find(id);
      if (found == outside.end()) found = outside.emplace(id, outside_corner(grid, system, cage, tree, corner)).first;
      for (const auto& [vertex, value] : found->second) outer.emplace_back(p, vertex, weight * value);
    }
    if (inside_corners < 8) ++result.boundary_cells;
    if (inside_corners == 0) ++result.unresolved;
  }
  result.inner.resize(n, static_cast<int>(system.node_of.size()));
  result.inner.setFromTriplets(inner.begin(), inner.end());
  result.outer.resize(n, cage.V.rows());
  result.outer.setFromTriplets(outer.begin(), outer.end());
  return result;
}

// Whether p is inside the cage: the first crossing of a ray from p leaves the cage (its triangle faces along
// the ray). The direction is off the axes so that grazing an edge of an axis-aligned cage is unlikely.
bool inside_cage(const RayCaster& caster, const Mesh& cage, const Eigen::Vector3d& p) {
  const Eigen::Vector3d direction(1.0, 0.0031415926, 0.0027182818);
  const RayHit hit = caster.first_hit(p, direction, 0.0, std::numeric_limits<double>::infinity());
  if (hit.face < 0) return false;
  const Eigen::Vector3d a = cage.V.row(cage.F(hit.face, 0)), b = cage.V.row(cage.F(hit.face, 1)),
                        c = cage.V.row(cage.F(hit.face, 2));
  return (b - a).cross(c - a).dot(direction) > 0;
}

void check_inside(const Vertices& points, const Mesh& cage) {
  const RayCaster caster(cage);
  std::vector<int> outside;
  for (int i = 0; i < points.rows(); ++i)
    if (!inside_cage(caster, cage, points.row(i).transpose())) outside.push_back(i);
  if (outside.empty()) return;
  std::ostringstream message;
  message << kWhat << ": " << outside.size() << " of " << points.rows()
          << " mesh vertices are outside the cage (first: ";
  for (size_t k = 0; k < outside.size() && k < 8; ++k) message << (k ? ", " : "") << outside[k];
  message << (outside.size() > 8 ? ", ...)" : ")")
          << "; every vertex must be strictly inside a closed, outward-oriented cage";
  throw Error(ErrorCode::MeshOutsideCage, message.str());
}

double longest_side(const Mesh& cage) { return (cage.V.colwise().maxCoeff() - cage.V.colwise().minCoeff()).maxCoeff(); }

// Bytes per unknown while the system is assembled and ordered (the triplets, A and R, the node indices, the
// permuted matrix and the ordering's workspace): measured about 190 on the bar, rounded up.
constexpr double kAssemblyBytesPerUnknown = 256;

// Before the grid exists: the unknowns from the cage's volume, and lower bounds of the factor's entries and
// work from the dense block the last separator leaves (one cross-section of the cage, about unknowns / nodes
// along the longest axis, eliminated last: s^2 / 2 entries and s^3 / 6 multiply-adds).
struct Estimate {
  double unknowns = 0, entries = 0, work = 0;
};

Estimate lower_estimate(const Mesh& cage, const Eigen::Array3i& counts, double spacing) {
  Estimate e;
  const double nodes = double(counts[0]) * counts[1] * counts[2];
  e.unknowns = std::min(nodes, std::max(signed_volume(cage.V, cage.F), 0.0) / (spacing * spacing * spacing));
  const double separator = e.unknowns / counts.maxCoeff();
  e.entries = separator * separator / 2;
  e.work = separator * separator * separator / 6;
  return e;
}

// What a resolution costs, for naming one that fits: the grid's bytes grow as r^3, the factor's entries as
// unknowns^1.6 ~ r^4.8 and its work as unknowns^2.3 ~ r^6.9 (AMD on the grids measured: the bar from 16k to
// 1.1M unknowns, where entries ~ 0.3 unknowns^1.6 and work ~ 0.06 unknowns^2.3); the solves' work grows as the
// entries. The scaling uses lower exponents and 90% of the allowance, so that the resolution named fits.
struct Cost {
  double grid_bytes = 0, factor_bytes = 0, factor_work = 0, solve_work = 0;
};

Cost modelled_cost(double unknowns, double grid_bytes, int m) {
  const double entries = 0.3 * std::pow(unknowns, 1.6);
  return {grid_bytes, entries * 12, 0.06 * std::pow(unknowns, 2.3), 2 * entries * m};
}

// The largest resolution below `resolution` whose cost, scaled from `cost` at `resolution`, fits; 0 if none.
int fitting_resolution(int resolution, const Cost& cost, double bytes_allowed, double work_allowed) {
  for (int r = resolution - 1; r >= HarmonicOptions::kMinResolution; --r) {
    const double scale = double(r) / resolution;
    const double bytes = cost.grid_bytes * std::pow(scale, 3) + cost.factor_bytes * std::pow(scale, 4.5);
    const double work = cost.factor_work * std::pow(scale, 6) + cost.solve_work * std::pow(scale, 4.5);
    if (bytes <= 0.9 * bytes_allowed && (work_allowed <= 0 || work <= 0.9 * work_allowed)) return r;
  }
  return 0;
}

std::string resolution_advice(int fits) {
  return fits > 0 ? "use resolution " + std::to_string(fits) + " or lower, or a coarser cage" : "use a coarser cage";
}

void check_budget(double bytes, double w_bytes, const MvcOptions& binding, const HarmonicOptions& options,
                  int resolution, const Cost& cost, const std::string& what) {
  if (w_bytes + bytes <= double(binding.memory_budget_bytes)) return;
  const int fits =
      fitting_resolution(resolution, cost, double(binding.memory_budget_bytes) - w_bytes, options.max_work);
  throw Error(ErrorCode::MemoryBudget, std::string(kWhat) + ": " + what + " would need " + megabytes(w_bytes + bytes) +
                                           " with W, over the memory budget of " +
                                           megabytes(double(binding.memory_budget_bytes)) + " at resolution " +
                                           std::to_string(resolution) + "; " + resolution_advice(fits) +
                                           ", or raise the budget");
}

std::string scaled(double value, double unit) {
  std::ostringstream out;
  out.precision(value < 10 * unit ? 2 : 0);
  out << std::fixed << value / unit;
  return out.str();
}

void check_work(double work, bool lower_bound, const MvcOptions& binding, const HarmonicOptions& options,
                int resolution, double w_bytes, const Cost& cost, const std::string& what) {
  if (options.max_work <= 0 || work <= options.max_work) return;
  const int fits =
      fitting_resolution(resolution, cost, double(binding.memory_budget_bytes) - w_bytes, options.max_work);
  throw Error(ErrorCode::InvalidArgument, std::string(kWhat) + ": " + what + " would take " +
                                              (lower_bound ? "at least " : "") + scaled(work, 1e9) +
                                              " G multiply-adds at resolution " + std::to_string(resolution) +
                                              ", over the limit of " + scaled(options.max_work, 1e9) +
                                              " G (about 10 s natively, up to a minute in a browser; "
                                              "docs/method.md section 19); " +
                                              resolution_advice(fits));
}

void report_progress(const MvcOptions& binding, double fraction) {
  if (binding.progress && !binding.progress(fraction)) throw Error(ErrorCode::Cancelled, "binding cancelled");
}

// The smallest entry of W and where it is (the first in row order on a tie), by blocks of rows.
MvcReport smallest_weight(const BasisMatrix& W) {
  MvcReport none;
  none.min_weight = std::numeric_limits<double>::infinity();
  MvcReport found = parallel::parallel_reduce(
      0, W.rows(), 1024, none,
      [&](int lo, int hi) {
        MvcReport part;
        part.min_weight = std::numeric_limits<double>::infinity();
        for (int i = lo; i < hi; ++i)
          for (int j = 0; j < W.cols(); ++j)
            if (W.get(i, j) < part.min_weight) {
              part.min_weight = W.get(i, j);
              part.min_weight_row = i;
              part.min_weight_col = j;
            }
        return part;
      },
      [](MvcReport a, const MvcReport& b) { return b.min_weight < a.min_weight ? b : a; });
  if (W.rows() == 0) found.min_weight = 0;
  return found;
}

// The grid, its factor and the solves, once the estimates allow them.
BasisMatrix solve(const Vertices& points, const Mesh& cage, const MvcOptions& binding, const HarmonicOptions& options,
                  MvcReport* report, HarmonicReport* details, HarmonicReport& local, const Eigen::Array3i& counts,
                  double w_bytes, const Timer& timer) {
  const int n = static_cast<int>(points.rows()), m = static_cast<int>(cage.V.rows());
  const double nodes = double(counts[0]) * counts[1] * counts[2];
  const CageGrid grid(cage, local.spacing);
  const AabbTree tree(triangle_boxes(cage.V, cage.F));
  const GridSystem system = assemble(grid, cage, tree);
  for (int a = 0; a < 3; ++a) local.grid[a] = counts[a];
  local.unknowns = static_cast<int>(system.node_of.size());
  if (local.unknowns == 0)
    throw Error(std::string(kWhat) + ": no grid node lies inside the cage at resolution " +
                std::to_string(local.resolution) + "; use a higher resolution");
  BlockLdlt factor(system.A);
  local.factor_nonzeros = factor.factor_nonzeros();
  const int threads = parallel::threads();
  // The grid, the system and the solves' blocks (growing as the unknowns), and the factor.
  const double grid_bytes = nodes * 5 + double(grid.crossing_count()) * sizeof(GridCrossing) +
                            double(system.A.nonZeros() + system.R.nonZeros()) * 12 + 100.0 * n +
                            double(local.unknowns) * (sizeof(Eigen::Vector3i) + 7 * 12) +
                            2.0 * threads * local.unknowns * kBlockColumns * sizeof(double);
  local.bytes = grid_bytes + factor.factor_bytes();
  // The solves stream the factor twice per right-hand side.
  const double solve_work = 2 * local.factor_nonzeros * m;
  local.work = factor.factor_work() + solve_work;
  const Cost counted{grid_bytes, factor.factor_bytes(), factor.factor_work(), solve_work};
  check_budget(local.bytes, w_bytes, binding, options, local.resolution, counted,
               "the factor of the grid Laplacian (" + std::to_string(local.unknowns) + " unknowns, " +
                   scaled(local.factor_nonzeros, 1e6) + " M entries)");
  check_work(local.work, false, binding, options, local.resolution, w_bytes, counted,
             "factoring the grid Laplacian (" + std::to_string(local.unknowns) + " unknowns) and solving for " +
                 std::to_string(m) + " cage vertices");
  // Progress: 0.02 after the ordering, then in proportion to the work, the factorization's row by row.
  const double share = 0.98 * factor.factor_work() / (factor.factor_work() + solve_work);
  report_progress(binding, 0.02);
  const Timer factor_timer;
  factor.factorize([&](double fraction) { report_progress(binding, 0.02 + share * fraction); });
  local.factor_seconds = factor_timer.ms() / 1e3;
  const double solved = 0.02 + share;
  report_progress(binding, solved);

  const Interpolation interpolate = interpolation(points, grid, system, cage, tree);
  local.boundary_cells = interpolate.boundary_cells;
  local.unresolved = interpolate.unresolved;
  BasisMatrix W(n, m, binding.single_precision);
  // Blocks of columns on the thread pool: each solves its right-hand sides, interpolates them and writes its
  // own columns of W. The calling thread reports progress between rounds of one block per thread.
  const Timer solve_timer;
  const Eigen::SparseMatrix<double> Rc = system.R;  // column-major: a block's columns are contiguous
  const int blocks = (m + kBlockColumns - 1) / kBlockColumns;
  for (int b0 = 0; b0 < blocks; b0 += threads) {
    const int b1 = std::min(blocks, b0 + threads);
    parallel::parallel_for(b0, b1, 1, [&](int lo, int hi) {
      for (int b = lo; b < hi; ++b) {
        const int j0 = b * kBlockColumns, width = std::min(m, j0 + kBlockColumns) - j0;
        BlockLdlt::Block X = Eigen::MatrixXd(Rc.middleCols(j0, width));
        factor.solve_in_place(X);
        const BlockLdlt::Block values = interpolate.inner * X;
        for (int i = 0; i < n; ++i)
          for (int j = 0; j < width; ++j) W.set(i, j0 + j, values(i, j));
      }
    });
    report_progress(binding, solved + (1 - solved) * double(b1) / blocks);
  }
  // The corners outside the cage: a few entries per point near it.
  for (int i = 0; i < n; ++i)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(interpolate.outer, i); it; ++it)
      W.set(i, static_cast<int>(it.col()), W.get(i, static_cast<int>(it.col())) + it.value());
  local.solve_seconds = solve_timer.ms() / 1e3;

  MvcReport summary = smallest_weight(W);
  summary.evaluations = double(local.unknowns) * m;
  summary.seconds = timer.ms() / 1e3;
  if (report) *report = summary;
  if (details) *details = local;
  return W;
}

}  // namespace

int harmonic_resolution(const Mesh& cage, const HarmonicOptions& options) {
  if (options.resolution != 0) return options.resolution;
  // About kDefaultInteriorNodes nodes inside: h^3 = volume / nodes.
  const double volume = std::max(signed_volume(cage.V, cage.F), 0.0);
  const double spacing = std::cbrt(volume / HarmonicOptions::kDefaultInteriorNodes);
  const double cells = spacing > 0 ? std::ceil(longest_side(cage) / spacing) : HarmonicOptions::kMinResolution;
  return static_cast<int>(
      std::clamp<double>(cells, HarmonicOptions::kMinResolution, HarmonicOptions::kDefaultMaxResolution));
}

BasisMatrix harmonic_coordinates(const Vertices& points, const Mesh& cage, const MvcOptions& binding,
                                 const HarmonicOptions& options, MvcReport* report, HarmonicReport* details) {
  const Timer timer;
  if (options.resolution != 0 &&
      (options.resolution < HarmonicOptions::kMinResolution || options.resolution > HarmonicOptions::kMaxResolution))
    throw Error(std::string(kWhat) + ": the resolution must be 0 (chosen from the cage) or an integer from " +
                std::to_string(HarmonicOptions::kMinResolution) + " to " +
                std::to_string(HarmonicOptions::kMaxResolution) + " (got " + std::to_string(options.resolution) + ")");
  const CageData data = prepare_cage(cage, kWhat);  // the cage's shape and indices checked as for MVC
  const int n = static_cast<int>(points.rows()), m = data.m;
  check_weights_budget(n, m, binding);
  check_points_finite(points, kWhat);
  HarmonicReport local;
  local.resolution = harmonic_resolution(cage, options);
  local.spacing = longest_side(cage) / local.resolution;
  const double w_bytes = double(n) * m * (binding.single_precision ? 4 : 8);
  // Before the grid: the grid (an inside flag and an unknown index per node), the assembly and ordering, and a
  // lower bound of the factor, against the budget; the lower bound of its work against the limit.
  const Eigen::Array3i counts = CageGrid::node_counts(cage, local.spacing);
  const double nodes = double(counts[0]) * counts[1] * counts[2];
  const Estimate estimate = lower_estimate(cage, counts, local.spacing);
  const double grid_bytes = nodes * 5 + estimate.unknowns * kAssemblyBytesPerUnknown;
  const Cost modelled = modelled_cost(estimate.unknowns, grid_bytes, m);
  const std::string grid_name = "the grid (" + std::to_string(counts[0]) + " x " + std::to_string(counts[1]) + " x " +
                                std::to_string(counts[2]) + " nodes, about " +
                                std::to_string(static_cast<long long>(estimate.unknowns)) + " inside)";
  check_budget(grid_bytes + estimate.entries * 12, w_bytes, binding, options, local.resolution, modelled,
               grid_name + " and its factor (at least " + scaled(estimate.entries, 1e6) + " M entries)");
  check_work(estimate.work, true, binding, options, local.resolution, w_bytes, modelled, "factoring " + grid_name);
  check_inside(points, cage);
  report_progress(binding, 0.0);
  try {
    return solve(points, cage, binding, options, report, details, local, counts, w_bytes, timer);
  } catch (const std::bad_alloc&) {
  } catch (const std::length_error&) {
  }
  throw Error(ErrorCode::MemoryBudget, std::string(kWhat) + ": out of memory at resolution " +
                                           std::to_string(local.resolution) + " (the grid has " +
                                           std::to_string(static_cast<long long>(nodes)) +
                                           " nodes); use a lower resolution or a coarser cage");
}

}  // namespace sd
