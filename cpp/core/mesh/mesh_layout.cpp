#include "core/mesh/mesh_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <unordered_map>
#include <string>

#include "core/error.h"
#include "core/geometry/aabb_tree.h"
#include "core/geometry/point_triangle_distance.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/topology.h"
#include "core/parts/partition.h"

namespace sd {
namespace {

// Unites the vertices at exactly the same position (-0 and +0 alike): sorting, so a million copies of one point
// cost n log n, not n^2.
void unite_equal_positions(const Vertices& V, DisjointSets& sets) {
  std::vector<std::pair<std::array<double, 3>, int>> keyed(static_cast<size_t>(V.rows()));
  for (int i = 0; i < V.rows(); ++i) keyed[i] = {{V(i, 0) + 0.0, V(i, 1) + 0.0, V(i, 2) + 0.0}, i};
  std::sort(keyed.begin(), keyed.end());
  for (size_t k = 1; k < keyed.size(); ++k)
    if (keyed[k].first == keyed[k - 1].first) sets.unite(keyed[k].second, keyed[k - 1].second);
}

// A well-mixed hash of a packed cell key (splitmix64's finaliser): grid keys are highly regular.
struct CellHash {
  size_t operator()(uint64_t x) const {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return static_cast<size_t>(x ^ (x >> 31));
  }
};

// Unites distinct positions closer than `tolerance` (the representatives of the equal ones only) through a grid
// of cells twice that size: a point's neighbours within the tolerance lie in its own cell or, along each axis,
// in the one cell on the side of the nearer face, so 8 cells are searched, not 27. A cell's points form a list
// threaded through `next`; cell coordinates are packed 21 bits each (offset by one, so the neighbours of cell
// 0 exist), enough for diagonal / tolerance up to 2^22 -- a smaller tolerance only makes distinct cells share
// a key, which costs comparisons, not correctness.
void unite_near_positions(const Vertices& V, double tolerance, DisjointSets& sets) {
  const Eigen::RowVector3d low = V.colwise().minCoeff();
  const double size = 2 * tolerance;
  const auto key = [](uint64_t x, uint64_t y, uint64_t z) {
    constexpr uint64_t mask = (1u << 21) - 1;
    return ((x & mask) << 42) | ((y & mask) << 21) | (z & mask);
  };
  std::unordered_map<uint64_t, int, CellHash> first;  // cell -> its last inserted point
  first.reserve(static_cast<size_t>(V.rows()));
  std::vector<int> next(static_cast<size_t>(V.rows()), -1);
  const double t2 = tolerance * tolerance;
  for (int i = 0; i < V.rows(); ++i) {
    if (sets.find(i) != i) continue;  // an equal position: its representative stands for it
    uint64_t cell[3], other[3];
    for (int a = 0; a < 3; ++a) {
      const double u = (V(i, a) - low[a]) / size;
      cell[a] = static_cast<uint64_t>(std::floor(u)) + 1;
      other[a] = u - std::floor(u) < 0.5 ? cell[a] - 1 : cell[a] + 1;  // the nearer neighbouring cell
    }
    for (int corner = 0; corner < 8; ++corner) {
      const auto it = first.find(
          key(corner & 1 ? other[0] : cell[0], corner & 2 ? other[1] : cell[1], corner & 4 ? other[2] : cell[2]));
      if (it == first.end()) continue;
      for (int j = it->second; j >= 0; j = next[j])
        if ((V.row(i) - V.row(j)).squaredNorm() <= t2) sets.unite(i, j);
    }
    const auto [it, added] = first.emplace(key(cell[0], cell[1], cell[2]), i);
    if (!added) {
      next[i] = it->second;
      it->second = i;
    }
  }
}

// Orthonormal frame of triangle abc (rows: the first edge's direction, normal x that, the unit normal); false
// when the triangle has collapsed.
bool face_frame(const Eigen::RowVector3d& a, const Eigen::RowVector3d& b, const Eigen::RowVector3d& c,
                Eigen::Matrix3d& frame) {
  const Eigen::RowVector3d e = b - a, n = e.cross(c - a);
  if (!(e.norm() > 0) || !(n.norm() > 0)) return false;
  frame.row(0) = e.normalized();
  frame.row(2) = n.normalized();
  frame.row(1) = frame.row(2).cross(frame.row(0));
  return frame.allFinite();
}

// The faces around an edge with more than two, paired with the neighbour (in angular order about the edge)
// that closes a solid wedge: a face walking the edge lo -> hi has its inside at decreasing angle, one walking
// hi -> lo at increasing angle, so the wedge from a backward face to the next forward one is inside. Returns
// false when the orientations do not alternate or two faces lie at the same angle (no pairing is defined).
bool pair_around_edge(const Vertices& V, int lo, int hi, const std::vector<std::pair<int, bool>>& faces, const Faces& F,
                      std::vector<std::pair<int, int>>& pairs) {
  const Eigen::RowVector3d u = (V.row(hi) - V.row(lo)).normalized();
  struct Around {
    double angle;
    int face;
    bool forward;
  };
  std::vector<Around> around;
  Eigen::RowVector3d r = Eigen::RowVector3d::Zero(), s = Eigen::RowVector3d::Zero();
  for (const auto& [f, forward] : faces) {
    int third = F(f, 0);
    for (int k = 0; k < 3; ++k)
      if (F(f, k) != lo && F(f, k) != hi) third = F(f, k);
    Eigen::RowVector3d w = V.row(third) - V.row(lo);
    w -= w.dot(u) * u;
    if (!(w.norm() > 0)) return false;
    if (around.empty()) r = w.normalized(), s = u.cross(r);
    around.push_back({std::atan2(w.dot(s), w.dot(r)), f, forward});
  }
  std::sort(around.begin(), around.end(), [](const Around& a, const Around& b) { return a.angle < b.angle; });
  const size_t m = around.size();
  for (size_t i = 0; i < m; ++i) {
    const Around& a = around[i];
    const Around& b = around[(i + 1) % m];
    if (a.forward == b.forward || std::abs(a.angle - b.angle) < 1e-12) return false;
  }
  const size_t first = around[0].forward ? 1 : 0;  // start at a backward face
  for (size_t i = first; i < m + first; i += 2) pairs.push_back({around[i % m].face, around[(i + 1) % m].face});
  return true;
}

// The bounding-box diagonal of the vertices the faces use.
double surface_diagonal(const Mesh& file) {
  Eigen::RowVector3d lo = Eigen::RowVector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::RowVector3d hi = -lo;
  for (Eigen::Index f = 0; f < file.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      lo = lo.cwiseMin(file.V.row(file.F(f, c)));
      hi = hi.cwiseMax(file.V.row(file.F(f, c)));
    }
  return (hi - lo).norm();
}

}  // namespace

MeshLayout::MeshLayout(const Mesh& file, const LayoutOptions& options) {
  stats_.file_vertices = static_cast<int>(file.V.rows());
  stats_.file_faces = static_cast<int>(file.F.rows());
  const bool indices_ok = file.F.size() == 0 || (file.F.minCoeff() >= 0 && file.F.maxCoeff() < file.V.rows());
  if (!(options.weld_tolerance >= 0 && options.weld_tolerance <= 1e-2))
    throw Error("mesh layout: the weld tolerance must be from 0 to 0.01 of the bounding-box diagonal (got " +
                std::to_string(options.weld_tolerance) + ")");
  // The tolerance scales with the surface: the vertices its faces use. A stray unused vertex far away (an
  // exporter's leftover at 1e5) would otherwise weld the whole surface into a point. Coordinates the check
  // refuses (beyond kMaxMeshCoordinate, non-finite) leave the file as it is, so that the check names them.
  const bool readable =
      file.V.allFinite() && (file.V.size() == 0 || !(file.V.cwiseAbs().maxCoeff() > kMaxMeshCoordinate));
  const double diagonal = indices_ok && readable ? surface_diagonal(file) : 0.0;
  if (file.F.rows() == 0 || !indices_ok || !readable) {
    set_identity(file);
    return;
  }
  weld(file, options.weld_tolerance * diagonal);
  split_non_manifold(solver_.V);
  attach_unreferenced(file);
  stats_.solver_vertices = static_cast<int>(solver_.V.rows());
  stats_.solver_faces = static_cast<int>(solver_.F.rows());
  identity_ =
      stats_.welded == 0 && stats_.unreferenced == 0 && stats_.collapsed_faces == 0 && stats_.split_vertices == 0;
}

void MeshLayout::set_identity(const Mesh& file) {
  identity_ = true;
  solver_ = file;
  const int n = static_cast<int>(file.V.rows()), m = static_cast<int>(file.F.rows());
  solver_of_file_.resize(n);
  std::iota(solver_of_file_.begin(), solver_of_file_.end(), 0);
  file_of_solver_ = solver_of_file_;
  solver_face_of_file_.resize(m);
  std::iota(solver_face_of_file_.begin(), solver_face_of_file_.end(), 0);
  file_face_of_solver_ = solver_face_of_file_;
  extra_start_.assign(static_cast<size_t>(n) + 1, 0);
  collapsed_at_.assign(static_cast<size_t>(m), -1);
  stats_.solver_vertices = n;
  stats_.solver_faces = m;
}

void MeshLayout::weld(const Mesh& file, double tolerance) {
  const int n = static_cast<int>(file.V.rows()), m = static_cast<int>(file.F.rows());
  DisjointSets sets(n);  // the root of a set is its lowest file index: the vertex that names the welded point
  unite_equal_positions(file.V, sets);
  if (tolerance > 0) unite_near_positions(file.V, tolerance, sets);
  // Faces on the welded points; a face whose corners weld together collapses.
  std::vector<char> referenced(static_cast<size_t>(n), 0), collapsed(static_cast<size_t>(m), 0);
  for (int f = 0; f < m; ++f) {
    const int a = sets.find(file.F(f, 0)), b = sets.find(file.F(f, 1)), c = sets.find(file.F(f, 2));
    collapsed[f] = a == b || b == c || c == a;
    if (!collapsed[f]) referenced[a] = referenced[b] = referenced[c] = 1;
  }
  collapsed_at_.assign(static_cast<size_t>(m), -1);
  // Solver vertices: the referenced points in the order of their lowest file index.
  std::vector<int> id(static_cast<size_t>(n), -1);
  for (int v = 0; v < n; ++v)
    if (sets.find(v) == v && referenced[v]) {
      id[v] = static_cast<int>(file_of_solver_.size());
      file_of_solver_.push_back(v);
    }
  solver_of_file_.resize(n);
  for (int v = 0; v < n; ++v) {
    solver_of_file_[v] = id[sets.find(v)];
    if (solver_of_file_[v] < 0) ++stats_.unreferenced;
  }
  stats_.welded = n - stats_.unreferenced - static_cast<int>(file_of_solver_.size());
  solver_.V.resize(static_cast<Eigen::Index>(file_of_solver_.size()), 3);
  for (size_t s = 0; s < file_of_solver_.size(); ++s)
    solver_.V.row(static_cast<Eigen::Index>(s)) = file.V.row(file_of_solver_[s]);
  solver_face_of_file_.assign(static_cast<size_t>(m), -1);
  std::vector<int> kept;
  for (int f = 0; f < m; ++f)
    if (!collapsed[f]) {
      solver_face_of_file_[f] = static_cast<int>(kept.size());
      kept.push_back(f);
    }
  stats_.collapsed_faces = m - static_cast<int>(kept.size());
  for (int f = 0; f < m; ++f)
    if (collapsed[f]) collapsed_at_[f] = solver_of_file_[file.F(f, 0)];
  file_face_of_solver_ = kept;
  solver_.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t s = 0; s < kept.size(); ++s)
    for (int k = 0; k < 3; ++k) solver_.F(static_cast<Eigen::Index>(s), k) = solver_of_file_[file.F(kept[s], k)];
}

void MeshLayout::split_non_manifold(const Vertices& V) {
  Faces& F = solver_.F;
  const int m = static_cast<int>(F.rows()), n = static_cast<int>(V.rows());
  const EdgeUses edges(F);
  // Corners (3 f + k) joined across each manifold or paired edge; the fans of a vertex are its corners' sets.
  DisjointSets corners(3 * m);
  const auto corner = [&](int f, int v) {
    for (int k = 0; k < 3; ++k)
      if (F(f, k) == v) return 3 * f + k;
    return 3 * f;
  };
  const auto join = [&](int f, int g, int lo, int hi) {
    corners.unite(corner(f, lo), corner(g, lo));
    corners.unite(corner(f, hi), corner(g, hi));
  };
  std::vector<std::pair<int, bool>> faces;  // the faces on one edge (reused)
  std::vector<std::pair<int, int>> pairs;
  for (const Edge& e : edges.edges()) {
    const EdgeUse* uses = edges.uses_of(e);
    if (e.faces == 2) join(uses[0].face, uses[1].face, e.lo, e.hi);  // the common case: a manifold edge
    if (e.non_manifold()) {
      faces.clear();
      pairs.clear();
      for (int k = 0; k < e.faces; ++k) faces.push_back({uses[k].face, uses[k].forward});
      if (pair_around_edge(V, e.lo, e.hi, faces, F, pairs)) ++stats_.paired_edges;
      else  // no pairing: the edge stays shared by all its faces (and the check names it)
        for (size_t k = 1; k < faces.size(); ++k) pairs.push_back({faces[0].first, faces[k].first});
      for (const auto& [f, g] : pairs) join(f, g, e.lo, e.hi);
    }
  }
  // Each vertex keeps its number for its first fan; every other fan gets a new vertex at the same place.
  std::vector<int> first_root(static_cast<size_t>(n), -1);
  std::map<int, int> copy_of_root;  // corner set -> its new vertex
  std::vector<int> new_vertices;    // the solver vertex each new one copies
  for (int f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const int v = F(f, k), root = corners.find(3 * f + k);
      if (first_root[v] < 0) first_root[v] = root;
      if (root == first_root[v]) continue;
      auto [it, added] = copy_of_root.emplace(root, n + static_cast<int>(new_vertices.size()));
      if (added) new_vertices.push_back(v);
      F(f, k) = it->second;
    }
  stats_.split_vertices = static_cast<int>(new_vertices.size());
  if (new_vertices.empty()) return;
  solver_.V.conservativeResize(n + static_cast<Eigen::Index>(new_vertices.size()), 3);
  std::vector<std::vector<int>> files_of(static_cast<size_t>(n));  // solver vertex -> its file vertices
  for (size_t v = 0; v < solver_of_file_.size(); ++v)
    if (solver_of_file_[v] >= 0) files_of[solver_of_file_[v]].push_back(static_cast<int>(v));
  std::vector<std::vector<int>> extra(solver_of_file_.size());
  for (size_t c = 0; c < new_vertices.size(); ++c) {
    const int copy = n + static_cast<int>(c), of = new_vertices[c];
    solver_.V.row(copy) = solver_.V.row(of);
    file_of_solver_.push_back(file_of_solver_[of]);
    for (int v : files_of[of]) extra[v].push_back(copy);
  }
  extra_start_.assign(1, 0);
  for (const auto& list : extra) {
    extra_copies_.insert(extra_copies_.end(), list.begin(), list.end());
    extra_start_.push_back(static_cast<int>(extra_copies_.size()));
  }
}

void MeshLayout::attach_unreferenced(const Mesh& file) {
  if (extra_start_.empty()) extra_start_.assign(solver_of_file_.size() + 1, 0);
  if (stats_.unreferenced == 0) return;
  const AabbTree tree(triangle_boxes(solver_.V, solver_.F));
  for (int v = 0; v < file.V.rows(); ++v) {
    if (solver_of_file_[v] >= 0) continue;
    const Eigen::Vector3d p = file.V.row(v).transpose();
    if (solver_.F.rows() == 0) {  // nothing to follow (every face collapsed): it stays where it is
      attachments_.push_back({v, Attachment{-1, Eigen::Vector3d::Zero(), p}});
      continue;
    }
    int nearest = 0;
    double best = std::numeric_limits<double>::infinity();
    const auto corner = [&](int f, int k) { return Eigen::Vector3d(solver_.V.row(solver_.F(f, k)).transpose()); };
    tree.minimum([&](const Box3& box) { return box.squaredExteriorDistance(p); },
                 [&](int f) {
                   const Eigen::Vector3d c0 = corner(f, 0), c1 = corner(f, 1), c2 = corner(f, 2);
                   const double d = point_triangle_squared_distance(p, c0, c1, c2);
                   if (d < best) best = d, nearest = f;
                   return d;
                 });
    attachments_.push_back({v, attachment(nearest, p)});
  }
}

MeshLayout::Attachment MeshLayout::attachment(int face, const Eigen::Vector3d& p) const {
  Eigen::Matrix3d corners;  // columns: the face's corners
  for (int k = 0; k < 3; ++k) corners.col(k) = solver_.V.row(solver_.F(face, k)).transpose();
  Attachment a;
  a.face = face;
  a.weights = closest_point_barycentric(p, corners.col(0), corners.col(1), corners.col(2));
  // The closest point as one matrix product: Emscripten 3.1.6 (-O3 -msimd128) miscompiled the same weighted
  // sum written term by term here (it came out as one corner), which no native build showed.
  const Eigen::Vector3d q = corners * a.weights;
  Eigen::Matrix3d frame;
  const bool framed =
      face_frame(corners.col(0).transpose(), corners.col(1).transpose(), corners.col(2).transpose(), frame);
  a.offset = framed ? Eigen::Vector3d(frame * (p - q)) : Eigen::Vector3d(p - q);
  return a;
}

std::vector<int> MeshLayout::solver_vertices(int file_vertex) const {
  std::vector<int> out;
  if (solver_of_file_[file_vertex] < 0) return out;
  out.push_back(solver_of_file_[file_vertex]);
  out.insert(out.end(), extra_copies_.begin() + extra_start_[file_vertex],
             extra_copies_.begin() + extra_start_[file_vertex + 1]);
  return out;
}

Vertices MeshLayout::to_file(const Vertices& X) const {
  if (X.rows() != solver_.V.rows())
    throw Error("mesh layout: " + std::to_string(X.rows()) + " positions for " + std::to_string(solver_.V.rows()) +
                " solver vertices");
  if (identity_) return X;
  Vertices out(stats_.file_vertices, 3);
  for (int v = 0; v < stats_.file_vertices; ++v) {
    if (solver_of_file_[v] < 0) continue;
    Eigen::RowVector3d sum = X.row(solver_of_file_[v]);
    for (int c = extra_start_[v]; c < extra_start_[v + 1]; ++c) sum += X.row(extra_copies_[c]);
    out.row(v) = sum / static_cast<double>(1 + extra_start_[v + 1] - extra_start_[v]);
  }
  for (const auto& [v, a] : attachments_) {
    if (a.face < 0) {
      out.row(v) = a.offset.transpose();
      continue;
    }
    Eigen::Matrix3d corners;  // rows: the face's corners (as attachment(), one matrix product for the point)
    for (int k = 0; k < 3; ++k) corners.row(k) = X.row(solver_.F(a.face, k));
    const Eigen::RowVector3d q = a.weights.transpose() * corners;
    Eigen::Matrix3d frame;
    // A triangle crushed flat by the deformation has no frame: the offset then keeps its rest direction.
    const bool framed = face_frame(corners.row(0), corners.row(1), corners.row(2), frame);
    out.row(v) =
        framed ? Eigen::RowVector3d(q + a.offset.transpose() * frame) : Eigen::RowVector3d(q + a.offset.transpose());
  }
  return out;
}

Eigen::VectorXd MeshLayout::values_to_file(const Eigen::VectorXd& values) const {
  if (values.size() != solver_.V.rows())
    throw Error("mesh layout: " + std::to_string(values.size()) + " values for " + std::to_string(solver_.V.rows()) +
                " solver vertices");
  if (identity_) return values;
  Eigen::VectorXd out = Eigen::VectorXd::Zero(stats_.file_vertices);
  for (int v = 0; v < stats_.file_vertices; ++v) {
    if (solver_of_file_[v] < 0) continue;
    double sum = values[solver_of_file_[v]];
    for (int c = extra_start_[v]; c < extra_start_[v + 1]; ++c) sum += values[extra_copies_[c]];
    out[v] = sum / static_cast<double>(1 + extra_start_[v + 1] - extra_start_[v]);
  }
  for (const auto& [v, a] : attachments_) {
    if (a.face < 0) continue;  // no solver face to follow: no value
    for (int k = 0; k < 3; ++k) out[v] += a.weights[k] * values[solver_.F(a.face, k)];
  }
  return out;
}

HandleMap MeshLayout::map_handles(const std::vector<std::vector<int>>& file_groups) const {
  HandleMap map;
  std::map<int, std::pair<int, int>> owner;  // solver vertex -> (group, file vertex)
  for (size_t g = 0; g < file_groups.size(); ++g) {
    if (file_groups[g].empty()) throw Error("handles: group " + std::to_string(g) + " is empty");
    std::vector<int> group;
    for (int v : file_groups[g]) {
      const int row = map.file_rows++;
      if (v < 0 || v >= stats_.file_vertices)
        throw Error("handles: group " + std::to_string(g) + " has vertex " + std::to_string(v) + " outside [0, " +
                    std::to_string(stats_.file_vertices) + ")");
      const std::vector<int> copies = solver_vertices(v);
      if (copies.empty())
        throw Error("handles: group " + std::to_string(g) + " has vertex " + std::to_string(v) +
                    ", which no triangle uses: it is carried along with the surface and cannot be a handle");
      for (int s : copies) {
        const auto [it, added] = owner.emplace(s, std::make_pair(static_cast<int>(g), v));
        if (added) {
          group.push_back(s);
          map.file_row.push_back(row);
          continue;
        }
        const auto [other_group, other_vertex] = it->second;
        const std::string same = other_vertex == v ? "vertex " + std::to_string(v)
                                                   : "vertices " + std::to_string(other_vertex) + " and " +
                                                         std::to_string(v) + " (one point: welded)";
        if (other_group == static_cast<int>(g)) {
          if (other_vertex == v)
            throw Error("handles: vertex " + std::to_string(v) + " appears twice in group " + std::to_string(g));
          continue;  // a welded copy of a vertex already in this group
        }
        throw Error("handles: " + same + " in both group " + std::to_string(other_group) + " and group " +
                    std::to_string(g));
      }
    }
    map.groups.push_back(std::move(group));
  }
  return map;
}

Vertices MeshLayout::solver_targets(const HandleMap& map, const Vertices& file_targets) const {
  if (file_targets.rows() != map.file_rows)
    throw Error("targets: " + std::to_string(file_targets.rows()) + " rows (" +
                std::to_string(3 * file_targets.rows()) + " numbers) for " + std::to_string(map.file_rows) +
                " handle vertices (expected " + std::to_string(3 * map.file_rows) + " numbers)");
  Vertices out(static_cast<Eigen::Index>(map.file_row.size()), 3);
  for (size_t r = 0; r < map.file_row.size(); ++r)
    out.row(static_cast<Eigen::Index>(r)) = file_targets.row(map.file_row[r]);
  return out;
}

std::vector<int> MeshLayout::solver_face_parts(const std::vector<int>& file_parts) const {
  if (static_cast<int>(file_parts.size()) != stats_.file_faces)
    throw Error("volume parts: " + std::to_string(file_parts.size()) + " part indices for " +
                std::to_string(stats_.file_faces) + " triangles (one per triangle expected)");
  std::vector<int> out(file_face_of_solver_.size());
  for (size_t s = 0; s < out.size(); ++s) out[s] = file_parts[file_face_of_solver_[s]];
  if (identity_) return out;
  compact_parts(out);
  return out;
}

std::vector<int> MeshLayout::file_face_parts(const std::vector<int>& solver_parts) const {
  std::vector<int> out(static_cast<size_t>(stats_.file_faces), 0);
  if (solver_parts.empty()) return {};
  // The part of some solver face at each solver vertex, for the collapsed faces.
  std::vector<int> part_at(static_cast<size_t>(solver_.V.rows()), 0);
  for (Eigen::Index s = solver_.F.rows() - 1; s >= 0; --s)
    for (int k = 0; k < 3; ++k) part_at[solver_.F(s, k)] = solver_parts[s];
  for (int f = 0; f < stats_.file_faces; ++f) {
    const int s = solver_face_of_file_[f];
    if (s >= 0) out[f] = solver_parts[s];
    else if (collapsed_at_[f] >= 0) out[f] = part_at[collapsed_at_[f]];
  }
  return out;
}

}  // namespace sd
