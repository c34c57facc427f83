#include "core/cage/internal/voxel_dilation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "core/geometry/aabb_tree.h"
#include "core/error.h"
#include "core/parallel/parallel_for.h"

namespace sd {
namespace {

constexpr double kMaxRadiusVoxels = 250;

// A voxel count for messages: whole numbers, also beyond the range of int.
std::string count_text(double count) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f", count);
  return text;
}

// Occupancy grid with a padded border so the outside is connected and reachable from cell (0, 0, 0).
struct Grid {
  int n[3];
  Eigen::RowVector3d origin;
  double h;
  std::vector<unsigned char> filled;

  long long index(int i, int j, int k) const { return (static_cast<long long>(i) * n[1] + j) * n[2] + k; }
  bool inside(int i, int j, int k) const { return i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2]; }
  bool at(int i, int j, int k) const { return inside(i, j, k) && filled[index(i, j, k)]; }
};

void mark_surface(const Mesh& mesh, Grid& grid, double spacing) {
  auto cell = [&](const Eigen::RowVector3d& p) {
    Eigen::Array3i c = ((p - grid.origin).array() / grid.h).floor().cast<int>();
    grid.filled[grid.index(c[0], c[1], c[2])] = 1;
  };
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::RowVector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int steps = std::max(1, static_cast<int>(std::ceil(longest / spacing)));
    for (int i = 0; i <= steps; ++i)
      for (int j = 0; i + j <= steps; ++j) cell(a + (b - a) * (double(i) / steps) + (c - a) * (double(j) / steps));
  }
}

// Squared distance, in voxel units, from every cell centre to the nearest surface-marked cell centre, exact
// (Felzenszwalb and Huttenlocher 2012: the lower envelope of parabolas, one 1D pass per axis), saturated at
// `cap`: farther cells read `cap`. O(cells), whatever the dilation radius.
std::vector<std::uint16_t> squared_distance_to_marked(const Grid& grid, std::uint16_t cap) {
  std::vector<std::uint16_t> d2(grid.filled.size());
  for (size_t id = 0; id < d2.size(); ++id) d2[id] = grid.filled[id] ? 0 : cap;
  const int longest = std::max({grid.n[0], grid.n[1], grid.n[2]});
  std::vector<double> f(longest), out(longest), z(longest + 1);
  std::vector<int> v(longest);
  const long long stride[3] = {static_cast<long long>(grid.n[1]) * grid.n[2], grid.n[2], 1};
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, w = (axis + 2) % 3, n = grid.n[axis];
    for (int a = 0; a < grid.n[u]; ++a)
      for (int b = 0; b < grid.n[w]; ++b) {
        const long long base = a * stride[u] + b * stride[w];
        for (int q = 0; q < n; ++q) f[q] = d2[base + q * stride[axis]];
        // Lower envelope of the parabolas (q - p)^2 + f[p] over the cells p nearer than the cap.
        int k = -1;
        for (int q = 0; q < n; ++q) {
          if (f[q] >= cap) continue;
          double s = 0;
          while (k >= 0 &&
                 (s = ((f[q] + double(q) * q) - (f[v[k]] + double(v[k]) * v[k])) / (2.0 * (q - v[k]))) <= z[k])
            --k;
          ++k;
          v[k] = q;
          z[k] = k == 0 ? -std::numeric_limits<double>::infinity() : s;
          z[k + 1] = std::numeric_limits<double>::infinity();
        }
        for (int q = 0, j = 0; q < n; ++q) {
          double value = cap;
          if (k >= 0) {
            while (z[j + 1] < q) ++j;
            value = std::min<double>(cap, double(q - v[j]) * (q - v[j]) + f[v[j]]);
          }
          out[q] = value;
        }
        for (int q = 0; q < n; ++q) d2[base + q * stride[axis]] = static_cast<std::uint16_t>(out[q]);
      }
  }
  return d2;
}

// Fills every voxel whose centre is within `reach` of the mesh. Candidates are the voxels whose centre is
// within `radius_cells` of a marked voxel's centre (a superset); each is then decided by its exact distance
// to the mesh (AABB tree). `report(fraction)` is called, on the calling thread, once per chunk of slabs.
void dilate(const Mesh& mesh, Grid& grid, double radius_cells, double reach,
            const std::function<void(double)>& report) {
  const double radius2 = radius_cells * radius_cells;
  const std::vector<std::uint16_t> d2 =
      squared_distance_to_marked(grid, static_cast<std::uint16_t>(std::ceil(radius2) + 1));
  const AabbTree tree(triangle_boxes(mesh.V, mesh.F));
  const double reach2 = reach * reach;
  auto decide_slab = [&](int i) {
    for (int j = 0; j < grid.n[1]; ++j)
      for (int k = 0; k < grid.n[2]; ++k) {
        const long long id = grid.index(i, j, k);
        if (grid.filled[id] || d2[id] > radius2) continue;
        const Eigen::Vector3d centre =
            (grid.origin + grid.h * Eigen::RowVector3d(i + 0.5, j + 0.5, k + 0.5)).transpose();
        if (squared_distance_to_triangles(tree, mesh, centre) <= reach2) grid.filled[id] = 1;
      }
  };
  // Each candidate is decided alone by its distance to the mesh: slabs of the grid (fixed i) on the thread
  // pool. The tree and d2 are only read, and each cell is read and written only by the slab that holds it.
  // The slabs go in chunks of a few per thread, and the calling thread reports between chunks: `report` may
  // call a JS progress callback (and throw Cancelled), which a pool thread cannot.
  const int chunk = 4 * parallel::threads();
  for (int c0 = 0; c0 < grid.n[0]; c0 += chunk) {
    report(double(c0) / grid.n[0]);
    parallel::parallel_for(c0, std::min(grid.n[0], c0 + chunk), 1, [&](int lo, int hi) {
      for (int i = lo; i < hi; ++i) decide_slab(i);
    });
  }
}

// Fills everything the outside cannot reach through face-adjacent empty cells. Returns true if it changed.
bool fill_cavities(Grid& grid) {
  std::vector<unsigned char> outside(grid.filled.size(), 0);
  std::vector<std::array<int, 3>> stack{{0, 0, 0}};
  outside[0] = 1;
  const int steps[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  while (!stack.empty()) {
    auto [i, j, k] = stack.back();
    stack.pop_back();
    for (const auto& s : steps) {
      const int a = i + s[0], b = j + s[1], c = k + s[2];
      if (!grid.inside(a, b, c)) continue;
      const long long id = grid.index(a, b, c);
      if (outside[id] || grid.filled[id]) continue;
      outside[id] = 1;
      stack.push_back({a, b, c});
    }
  }
  bool changed = false;
  for (size_t id = 0; id < outside.size(); ++id)
    if (!outside[id] && !grid.filled[id]) {
      grid.filled[id] = 1;
      changed = true;
    }
  return changed;
}

// One pass over every 2x2 square (three orientations) and 2x2x2 block, filling critical configurations.
bool fix_critical_configurations(Grid& grid) {
  bool changed = false;
  for (int i = 0; i + 1 < grid.n[0]; ++i)
    for (int j = 0; j + 1 < grid.n[1]; ++j)
      for (int k = 0; k + 1 < grid.n[2]; ++k) {
        int cells[8][3];
        bool v[8];
        int count = 0;
        for (int b = 0; b < 8; ++b) {
          cells[b][0] = i + (b & 1);
          cells[b][1] = j + ((b >> 1) & 1);
          cells[b][2] = k + ((b >> 2) & 1);
          v[b] = grid.at(cells[b][0], cells[b][1], cells[b][2]);
          count += v[b];
        }
        bool critical = false;
        // Vertex-critical: exactly two cells (filled or empty) at opposite corners of the block.
        if (count == 2 || count == 6) {
          const bool minority = count == 2;
          for (int b = 0; b < 4 && !critical; ++b) critical = v[b] == minority && v[7 - b] == minority;
        }
        // Edge-critical: a 2x2 face of the block (there are 6) with a diagonal pattern.
        const int faces[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
        for (int f = 0; f < 6 && !critical; ++f) {
          const int* q = faces[f];
          critical = v[q[0]] == v[q[2]] && v[q[1]] == v[q[3]] && v[q[0]] != v[q[1]];
        }
        if (!critical) continue;
        for (int b = 0; b < 8; ++b) grid.filled[grid.index(cells[b][0], cells[b][1], cells[b][2])] = 1;
        changed = true;
      }
  return changed;
}

Mesh boundary_surface(const Grid& grid) {
  const long long corners_per_slab = static_cast<long long>(grid.n[1] + 1) * (grid.n[2] + 1);
  std::vector<int> corner_id(static_cast<size_t>((grid.n[0] + 1) * corners_per_slab), -1);
  std::vector<std::array<int, 3>> points;
  std::vector<std::array<int, 3>> triangles;
  auto corner = [&](int i, int j, int k) {
    const long long key = i * corners_per_slab + static_cast<long long>(j) * (grid.n[2] + 1) + k;
    if (corner_id[key] < 0) {
      corner_id[key] = static_cast<int>(points.size());
      points.push_back({i, j, k});
    }
    return corner_id[key];
  };
  for (int i = 0; i < grid.n[0]; ++i)
    for (int j = 0; j < grid.n[1]; ++j)
      for (int k = 0; k < grid.n[2]; ++k) {
        if (!grid.filled[grid.index(i, j, k)]) continue;
        const int c[3] = {i, j, k};
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {1, -1}) {
            int nb[3] = {i, j, k};
            nb[axis] += sign;
            if (grid.at(nb[0], nb[1], nb[2])) continue;
            // Quad in the plane axis = c[axis] (+1 for the + side); u, v complete a right-handed frame so
            // (u0,v0),(u1,v0),(u1,v1),(u0,v1) is counter-clockwise seen from +axis.
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            int q[4];
            for (int m = 0; m < 4; ++m) {
              int p[3];
              p[axis] = c[axis] + (sign > 0 ? 1 : 0);
              p[u] = c[u] + ((m == 1 || m == 2) ? 1 : 0);
              p[w] = c[w] + ((m >= 2) ? 1 : 0);
              q[m] = corner(p[0], p[1], p[2]);
            }
            if (sign < 0) std::swap(q[1], q[3]);
            triangles.push_back({q[0], q[1], q[2]});
            triangles.push_back({q[0], q[2], q[3]});
          }
      }
  Mesh out;
  out.V.resize(static_cast<int>(points.size()), 3);
  for (size_t p = 0; p < points.size(); ++p)
    for (int a = 0; a < 3; ++a) out.V(static_cast<int>(p), a) = grid.origin[a] + points[p][a] * grid.h;
  out.F.resize(static_cast<int>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t)
    out.F.row(static_cast<int>(t)) << triangles[t][0], triangles[t][1], triangles[t][2];
  return out;
}

}  // namespace

Mesh dilated_voxel_surface(const Mesh& mesh, double offset, double voxel_size, long long max_cells,
                           const std::function<bool(double)>& progress) {
  if (mesh.V.rows() == 0 || mesh.F.rows() == 0)
    throw Error(ErrorCode::InvalidMesh, "voxel dilation: the mesh is empty");
  if (!(offset > 0) || !(voxel_size > 0) || !std::isfinite(offset) || !std::isfinite(voxel_size))
    throw Error("voxel dilation: offset and voxel size must be positive finite lengths (got " + std::to_string(offset) +
                ", " + std::to_string(voxel_size) + ")");
  const double h = voxel_size;
  const double spacing = 0.5 * h;
  const double radius = offset + std::sqrt(3.0) * h + spacing;
  // The distance transform counts squared voxel distances in 16 bits.
  if (radius / h > kMaxRadiusVoxels)
    throw Error("voxel dilation: the offset is " + count_text(offset / h) + " voxels, over the limit of " +
                count_text(kMaxRadiusVoxels - 3) + "; use a larger voxel size");
  // Sizes in double first: a far offset or a tiny voxel must be refused here, not overflow an int.
  const double pad = std::ceil(radius / h) + 2;
  const Eigen::RowVector3d lo = mesh.V.colwise().minCoeff(), hi = mesh.V.colwise().maxCoeff();
  double extent[3], cells = 1;
  for (int a = 0; a < 3; ++a) {
    extent[a] = std::ceil((hi[a] - lo[a]) / h) + 2 * pad + 1;
    cells *= extent[a];
  }
  if (!(cells <= double(max_cells)))
    throw Error(ErrorCode::MemoryBudget, "voxel dilation: a grid of " + count_text(extent[0]) + " x " +
                                             count_text(extent[1]) + " x " + count_text(extent[2]) +
                                             " voxels is over the limit of " + std::to_string(max_cells) +
                                             " voxels; use a larger voxel size or a smaller offset");
  Grid grid;
  grid.h = h;
  grid.origin = lo - Eigen::RowVector3d::Constant(pad * h);
  for (int a = 0; a < 3; ++a) grid.n[a] = static_cast<int>(extent[a]);
  auto report = [&](double fraction) {
    if (progress && !progress(fraction)) throw Error(ErrorCode::Cancelled, "cage generation cancelled");
  };
  grid.filled.assign(static_cast<size_t>(cells), 0);
  mark_surface(mesh, grid, spacing);
  // Any point within `offset` of the mesh lies in a voxel whose centre is within offset + sqrt(3)/2 h of it.
  // The exact distances of the dilation are most of the work: 90% of the progress.
  dilate(mesh, grid, radius / h, offset + 0.5 * std::sqrt(3.0) * h * (1 + 1e-9), [&](double f) { report(0.9 * f); });
  fill_cavities(grid);
  for (int round = 0; round < 100; ++round) {
    const bool fixed = fix_critical_configurations(grid);
    const bool filled = fill_cavities(grid);
    if (!fixed && !filled) break;
  }
  report(1.0);
  return boundary_surface(grid);
}

}  // namespace sd
