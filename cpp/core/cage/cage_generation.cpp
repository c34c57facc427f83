#include "core/cage/cage_generation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/geometry/aabb_tree.h"
#include "core/error.h"
#include "core/cage/internal/progressive_hull.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_layout.h"
#include "core/mesh/volume.h"
#include "core/parts/part_volume.h"
#include "core/parts/partition.h"
#include "core/geometry/self_intersection.h"
#include "core/geometry/winding_number.h"
#include "core/cage/internal/voxel_dilation.h"

namespace sd {
namespace {

// Why collapses run out on a model of separate parts: parts farther apart than about twice the offset give the
// offset surface one closed piece each, and every piece keeps the few vertices a closed surface needs. An attack's
// three spheres 50 apart ran out at 19 vertices of 12 with no word of the parts.
std::string pieces_advice(const Mesh& start) {
  const std::vector<int> component = component_parts(start.F);
  const int pieces = component.empty() ? 0 : *std::max_element(component.begin(), component.end()) + 1;
  if (pieces < 2) return "";
  return "; the offset surface has " + std::to_string(pieces) +
         " separate pieces (the model's parts lie farther apart than twice the offset) and each needs its own closed "
         "surface: ask for more vertices, a larger offset, or cage the parts apart";
}

using Vec3 = Eigen::Vector3d;

// The volume of a closed surface (a cage, the model's capped surface), about its own reference point (volume.h):
// summed about the origin, a model far from it lost the digits of its volume ratios.
double enclosed_volume(const Mesh& m) { return signed_volume(m.V, m.F); }

double min_vertex_distance(const Mesh& mesh, const Mesh& cage) {
  const AabbTree tree(triangle_boxes(cage.V, cage.F));
  double best = std::numeric_limits<double>::infinity();
  for (int v = 0; v < mesh.V.rows(); ++v) {
    best = std::min(best, squared_distance_to_triangles(tree, cage, mesh.V.row(v).transpose()));
  }
  return std::sqrt(best);
}

// "" when closed, edge- and vertex-manifold and consistently oriented with every vertex used.
std::string topology_defect(const Mesh& m) {
  const int n = static_cast<int>(m.V.rows());
  std::map<std::pair<int, int>, int> directed;
  std::vector<std::vector<std::pair<int, int>>> around(n);  // per vertex: (next, previous) of each face
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.F(f, k), b = m.F(f, (k + 1) % 3), c = m.F(f, (k + 2) % 3);
      if (a < 0 || a >= n)
        return "face " + std::to_string(f) + " has vertex index " + std::to_string(a) + " out of range";
      if (a == b) return "face " + std::to_string(f) + " is degenerate (repeated vertex)";
      if (++directed[{a, b}] > 1)
        return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ") is used twice in the same direction";
      around[a].push_back({b, c});
    }
  for (const auto& [edge, count] : directed)
    if (!directed.count({edge.second, edge.first}))
      return "edge (" + std::to_string(edge.first) + ", " + std::to_string(edge.second) + ") is a border (not closed)";
  for (int v = 0; v < n; ++v) {
    if (around[v].empty()) return "vertex " + std::to_string(v) + " is not used by any face";
    // The faces around v must form one cycle (next of one face = previous of the following one).
    std::map<int, int> step;
    for (const auto& [next, previous] : around[v]) step[next] = previous;
    int x = around[v][0].first, count = 0;
    do {
      auto it = step.find(x);
      if (it == step.end()) break;
      x = it->second;
      ++count;
    } while (x != around[v][0].first && count <= static_cast<int>(around[v].size()));
    if (count != static_cast<int>(around[v].size()))
      return "vertex " + std::to_string(v) + " is non-manifold (its faces form more than one fan)";
  }
  return "";
}

// The most voxels of the dilation grid (about 64 MB for its occupancy, 128 MB for its distances).
constexpr long long kMaxVoxels = 64LL << 20;
// Voxels per offset, at least: a far cage needs no fine grid, and a bounded ratio bounds the grid, the
// dilation's work and the voxel surface the hull decimates whatever the offset. Default offsets are far
// below this and keep the resolution's voxels.
constexpr double kOffsetVoxels = 8;

// A length or count for messages ("1e+30", "3.464").
std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", x);
  return text;
}

// Refuses what no cage can be made for, naming the problem: the model must pass check_model (manifold once
// welded, consistently and outward oriented, finite, no degenerate or duplicate faces, some volume; open is
// fine: the holes are capped), and the sizes must be sane.
void check_input(const MeshLayout& layout, const CageOptions& options) {
  const Mesh& mesh = layout.mesh();
  const CheckReport report = check_model(layout);
  if (!report.ok()) throw MeshError(report, "cage generation needs a valid mesh:\n");
  const int target = options.target_vertices;
  if (target < kMinCageVertices || target > kMaxCageVertices)
    throw Error("cage generation: the target vertex count must be from " + std::to_string(kMinCageVertices) + " to " +
                std::to_string(kMaxCageVertices) + " (got " + std::to_string(target) + ")");
  const double diagonal = bounding_box_diagonal(mesh.V);
  if (!std::isfinite(options.offset) || options.offset > diagonal)
    throw Error("cage generation: the offset must be a length of at most the mesh's bounding-box diagonal (" +
                number(diagonal) + "; got " + number(options.offset) +
                "): a cage farther out barely controls the mesh");
  if (options.resolution > kMaxCageResolution)
    throw Error("cage generation: the resolution must be at most " + std::to_string(kMaxCageResolution) +
                " voxels along the longest side (got " + std::to_string(options.resolution) + ")");
  if (options.resolution > 0 && options.resolution < kMinCageResolution)
    throw Error("cage generation: the resolution must be at least " + std::to_string(kMinCageResolution) +
                " voxels along the longest side, or 0 for automatic (got " + std::to_string(options.resolution) + ")");
}

}  // namespace

std::string cage_defect(const Mesh& mesh, const Mesh& cage, double tol) {
  std::string topology = topology_defect(cage);
  if (!topology.empty()) return "cage: " + topology;
  if (!(enclosed_volume(cage) > 0)) return "cage is inward oriented (its volume is not positive)";
  const auto self = self_intersections(cage, tol, 1);
  if (!self.empty())
    return "cage faces " + std::to_string(self[0].first) + " and " + std::to_string(self[0].second) + " intersect";
  const auto crossing = surface_crossings(mesh, cage, tol, 1);
  if (!crossing.empty())
    return "mesh face " + std::to_string(crossing[0].first) + " touches cage face " +
           std::to_string(crossing[0].second);
  int outside = 0, first = -1;
  for (int v = 0; v < mesh.V.rows(); ++v)
    if (winding_number(cage, mesh.V.row(v)) < 0.5) {
      if (outside++ == 0) first = v;
    }
  if (outside > 0)
    return std::to_string(outside) + " mesh vertices are outside the cage (first: vertex " + std::to_string(first) +
           ")";
  return "";
}

namespace {

// The surface the cage must enclose: the model welded (mesh_layout.h) with every hole closed by the fan from
// its centroid, as its volume is (part_volume.h).
Mesh closed_surface(const MeshLayout& layout) {
  const Mesh& m = layout.mesh();
  return PartVolumes(m.F, static_cast<int>(m.V.rows()), std::vector<int>(static_cast<size_t>(m.F.rows()), 0))
      .closed_mesh(m.V);
}

}  // namespace

CageResult generate_cage(const Mesh& model, const CageOptions& options) {
  const int K = options.target_vertices;
  const MeshLayout layout(model);
  check_input(layout, options);
  const Mesh mesh = closed_surface(layout);
  const double diagonal = bounding_box_diagonal(mesh.V);
  const double longest = (mesh.V.colwise().maxCoeff() - mesh.V.colwise().minCoeff()).maxCoeff();
  const double tol = 1e-9 * diagonal;
  double offset = options.offset > 0 ? options.offset : 0.005 * diagonal;
  // Voxels along the longest side: enough surface vertices for K, few enough to decimate quickly.
  int resolution = options.resolution > 0
                       ? options.resolution
                       : std::clamp(static_cast<int>(std::lround(2.5 * std::sqrt(double(K)))) + 24, 32, 128);

  double offset_voxels = kOffsetVoxels;
  double progress_low = 0.0;
  std::string last_problem;
  for (int attempt = 1; attempt <= std::max(1, options.max_attempts); ++attempt) {
    const double span = (1.0 - progress_low) * 0.95;
    auto report = [&](double fraction) {
      if (options.progress && !options.progress(progress_low + span * std::clamp(fraction, 0.0, 1.0)))
        throw Error(ErrorCode::Cancelled, "cage generation cancelled");
    };
    report(0.0);
    const double h = std::max(longest / resolution, offset / offset_voxels);
    Mesh start = dilated_voxel_surface(mesh, offset, h, kMaxVoxels, [&](double fraction) {
      report(0.1 * fraction);
      return true;
    });
    if (start.V.rows() < K) {
      last_problem = "the voxel surface has only " + std::to_string(start.V.rows()) + " vertices (fewer than " +
                     std::to_string(K) + ") even on the finest grid tried";
      resolution = std::min(kMaxCageResolution, static_cast<int>(resolution * 1.5));
      offset_voxels *= 1.5;
      progress_low += span;
      continue;
    }
    ProgressiveHullOptions hull_options;
    hull_options.target_vertices = K;
    hull_options.obstacle = &mesh;
    hull_options.clearance = 0.5 * offset;
    hull_options.tolerance = tol;
    hull_options.progress = [&](double fraction) {
      if (options.progress && !options.progress(progress_low + span * (0.1 + 0.75 * fraction))) return false;
      return true;
    };
    Mesh cage = progressive_hull(start, hull_options);
    report(0.85);
    if (cage.V.rows() > K + K / 5) {
      last_problem = "collapses ran out at " + std::to_string(cage.V.rows()) + " vertices (target " +
                     std::to_string(K) + ", offset " + std::to_string(offset) + ")" + pieces_advice(start);
    } else {
      last_problem = cage_defect(mesh, cage, tol);
    }
    if (last_problem.empty()) {
      CageResult result;
      result.offset = offset;
      result.voxel_size = h;
      result.attempts = attempt;
      result.start_vertices = static_cast<int>(start.V.rows());
      const double mesh_volume = enclosed_volume(mesh);
      result.volume_ratio = mesh_volume > 0 ? enclosed_volume(cage) / mesh_volume : 0.0;
      result.start_volume_ratio = mesh_volume > 0 ? enclosed_volume(start) / mesh_volume : 0.0;
      result.min_clearance = min_vertex_distance(mesh, cage);
      result.cage = std::move(cage);
      if (options.progress) options.progress(1.0);
      return result;
    }
    offset *= 1.6;  // more room: nearby parts merge in the voxel surface and collapses are refused less
    progress_low += span;
  }
  throw Error(ErrorCode::CageFailed, "cage generation: no valid cage of " + std::to_string(K) + " vertices after " +
                                         std::to_string(std::max(1, options.max_attempts)) +
                                         " attempts; last problem: " + last_problem);
}

}  // namespace sd
