#include "core/parts/part_volume.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/error.h"
#include "core/mesh/volume.h"
#include "core/parallel/parallel_for.h"
#include "core/parts/partition.h"

namespace sd {
namespace {

using Row = Eigen::RowVector3d;

double det(const Row& u, const Row& v, const Row& w) { return u.cross(v).dot(w); }

Row centroid(const Vertices& X, const std::vector<int>& vertices, const Row& o = Row::Zero()) {
  Row sum = Row::Zero();
  for (int v : vertices) sum += X.row(v) - o;
  return sum / static_cast<double>(vertices.size());
}

long long edge_key(int a, int b, int n) { return static_cast<long long>(a) * n + b; }

// A component whose |volume| is below this times its own cubed bounding-box diagonal encloses nothing (the flat
// threshold of mesh_check, which measures the whole mesh against its whole box).
constexpr double kFlatPartRatio = 1e-12;
// At most this many default parts: each is a constraint of every iteration with a dense #V x 3 gradient, so a
// model of thousands of pieces (a scan's debris, a pile of bolts) must not make thousands of them.
constexpr int kMaxDefaultParts = 32;

// Whether some edge has a single triangle (a sort of the undirected edges: no hash map, as this runs for every
// model loaded).
bool has_boundary(const Faces& F) {
  std::vector<long long> edges;
  edges.reserve(3 * static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const long long a = F(f, k), b = F(f, (k + 1) % 3);
      edges.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) return true;
    i = j;
  }
  return false;
}

}  // namespace

PartVolumes::PartVolumes(const Faces& F, int vertex_count, const std::vector<int>& part_of_face)
    : F_(F), around_(vertex_triangles(vertex_count, F)), part_(part_of_face) {
  if (static_cast<Eigen::Index>(part_.size()) != F.rows())
    throw Error("volume parts: " + std::to_string(part_.size()) + " part indices for " + std::to_string(F.rows()) +
                " triangles");
  for (int p : part_) {
    if (p < 0) throw Error("volume parts: negative part index " + std::to_string(p));
    count_ = std::max(count_, p + 1);
  }
  find_curves(vertex_count);
}

void PartVolumes::find_curves(int n) {
  // Interface half-edges a -> b as the lower part's triangle runs them, grouped by the pair of parts.
  std::unordered_map<long long, int> face_of;  // directed edge -> its triangle
  face_of.reserve(static_cast<size_t>(3 * F_.rows()));
  for (int f = 0; f < F_.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F_(f, k), b = F_(f, (k + 1) % 3);
      if (!face_of.emplace(edge_key(a, b, n), f).second)
        throw Error(ErrorCode::InvalidMesh, "volume parts: edge " + std::to_string(a) + "-" + std::to_string(b) +
                                                " is run in the same direction by two triangles (non-manifold or "
                                                "inconsistently oriented)");
    }
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> by_pair;
  for (int f = 0; f < F_.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F_(f, k), b = F_(f, (k + 1) % 3);
      // A boundary edge faces the outside, numbered K: after every part, so the pair is (part, K).
      const auto across = face_of.find(edge_key(b, a, n));
      const int p = part_[f], q = across == face_of.end() ? count_ : part_[across->second];
      if (p < q) by_pair[{p, q}].push_back({a, b});
    }
  // Junctions: vertices on interfaces of two or more pairs, or where one pair's curve branches or ends.
  std::vector<std::map<std::pair<int, int>, int>> degree(static_cast<size_t>(n));
  for (const auto& [pair, edges] : by_pair)
    for (const auto& [a, b] : edges) {
      ++degree[a][pair];
      ++degree[b][pair];
    }
  std::vector<char> junction(static_cast<size_t>(n), 0);
  for (int v = 0; v < n; ++v) {
    bool is_junction = degree[v].size() >= 2;
    for (const auto& entry : degree[v]) is_junction = is_junction || entry.second != 2;
    if (is_junction) {
      junction[v] = 1;
      junctions_.push_back(v);
    }
  }
  // Trace each pair's edges into paths between junctions, then the closed loops left.
  for (const auto& entry : by_pair) {
    // (Named references, not a structured binding: lambdas may not capture those before C++20.)
    const std::pair<int, int>& pair = entry.first;
    const std::vector<std::pair<int, int>>& edges = entry.second;
    std::unordered_map<int, std::vector<int>> out;  // tail vertex -> indices of its half-edges
    for (size_t e = 0; e < edges.size(); ++e) out[edges[e].first].push_back(static_cast<int>(e));
    std::vector<char> used(edges.size(), 0);
    const auto next_from = [&](int v) {
      for (int e : out[v])
        if (!used[e]) return e;
      return -1;
    };
    const auto trace = [&](int first, bool stop_at_junctions) {
      Curve c;
      c.p = pair.first;
      c.q = pair.second;
      c.closed = !stop_at_junctions;
      c.start = edges[first].first;
      c.vertices.push_back(c.start);
      for (int e = first; e >= 0;) {
        used[e] = 1;
        c.edges.push_back(edges[e]);
        const int head = edges[e].second;
        if (stop_at_junctions && junction[head]) {
          c.end = head;
          c.vertices.push_back(head);
          break;
        }
        if (head == c.start) break;  // a closed loop is back where it began
        c.vertices.push_back(head);
        e = next_from(head);
      }
      curves_.push_back(std::move(c));
    };
    for (size_t e = 0; e < edges.size(); ++e)
      if (!used[e] && junction[edges[e].first]) trace(static_cast<int>(e), true);
    for (size_t e = 0; e < edges.size(); ++e)
      if (!used[e]) trace(static_cast<int>(e), false);
  }
  // A path that starts and ends at the same junction has a zero chord; its vertex list holds that junction
  // twice, which would weigh it double in the centroid.
  for (Curve& c : curves_)
    if (!c.closed && c.start == c.end) c.vertices.pop_back();
}

int PartVolumes::boundary_curve_count() const {
  return static_cast<int>(std::count_if(curves_.begin(), curves_.end(), [&](const Curve& c) { return c.q == count_; }));
}

Row PartVolumes::junction_centre(const Vertices& X, const VolumeReference& r) const {
  return junctions_.empty() ? Row::Zero() : centroid(X, junctions_, r);
}

Eigen::VectorXd PartVolumes::evaluate(const Vertices& X, const VolumeReference& r) const {
  // The triangles' sums as signed_volume forms them (one part: its bits), then each part's caps, every point
  // relative to r as the triangles' are (volume.h: about the origin a far model's terms cancel).
  const Eigen::VectorXd volumes = signed_volumes(X, F_, part_, count_, r);
  if (curves_.empty()) return volumes;
  Eigen::VectorXd caps = Eigen::VectorXd::Zero(count_);
  const Row o = junction_centre(X, r);
  const auto at = [&](int v) -> Row { return X.row(v) - r; };
  for (const Curve& curve : curves_) {
    const Row c = centroid(X, curve.vertices, r);
    double cap = 0.0;
    for (const auto& [a, b] : curve.edges) cap += det(at(b), at(a), c);
    if (!curve.closed) cap += det(c, at(curve.start), at(curve.end)) + det(at(curve.end), at(curve.start), o);
    caps[curve.p] += cap;
    if (curve.q < count_) caps[curve.q] -= cap;
  }
  return volumes + caps / 6.0;
}

Mesh PartVolumes::closed_mesh(const Vertices& X) const {
  if (count_ != 1) throw Error("volume parts: only a single part's mesh can be closed by its caps");
  Mesh out;
  out.V = X;
  out.F = F_;
  for (const Curve& curve : curves_) {  // one part: every curve is a hole, closed
    const int c = static_cast<int>(out.V.rows());
    out.V.conservativeResize(c + 1, 3);
    out.V.row(c) = centroid(X, curve.vertices);
    const Eigen::Index first = out.F.rows();
    out.F.conservativeResize(first + static_cast<Eigen::Index>(curve.edges.size()), 3);
    for (size_t e = 0; e < curve.edges.size(); ++e)
      out.F.row(first + static_cast<Eigen::Index>(e)) << curve.edges[e].second, curve.edges[e].first, c;
  }
  return out;
}

Eigen::MatrixXd PartVolumes::gradients(const Vertices& X, const VolumeReference& r) const {
  // d/du (u x v).w = v x w, d/dv = w x u, d/dw = u x v: the triangle terms as in volume_gradient, then each cap
  // triangle's, with the centroids' and o's shares spread evenly over the vertices they average.
  const Eigen::Index n = X.rows();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, 3 * count_);
  const auto add = [&](int vertex, int part, const Row& g) { G.block<1, 3>(vertex, 3 * part) += g; };
  // The triangle terms gathered per vertex, its triangles in increasing order (as volume_gradient: the same sums
  // whatever the thread count), in parallel over blocks of vertices.
  parallel::parallel_for(0, static_cast<int>(n), 2048, [&](int lo, int hi) {
    for (int v = lo; v < hi; ++v)
      for (int s = around_.start[v]; s < around_.start[v + 1]; ++s) {
        const int f = around_.triangle[s], k = around_.corner[s];
        add(v, part_[f], (X.row(F_(f, (k + 1) % 3)) - r).cross(X.row(F_(f, (k + 2) % 3)) - r));
      }
  });
  const Row o = junction_centre(X, r);
  std::vector<Row> o_share(static_cast<size_t>(count_), Row::Zero());
  for (const Curve& curve : curves_) {
    const Row c = centroid(X, curve.vertices, r);
    Row c_share = Row::Zero(), o_part = Row::Zero();
    std::vector<std::pair<int, Row>> terms;
    terms.reserve(2 * curve.edges.size() + 4);
    for (const auto& [a, b] : curve.edges) {
      const Row xa = X.row(a) - r, xb = X.row(b) - r;
      terms.push_back({b, xa.cross(c)});
      terms.push_back({a, c.cross(xb)});
      c_share += xb.cross(xa);
    }
    if (!curve.closed) {
      const Row xs = X.row(curve.start) - r, xe = X.row(curve.end) - r;
      c_share += xs.cross(xe);
      terms.push_back({curve.start, xe.cross(c) + o.cross(xe)});
      terms.push_back({curve.end, c.cross(xs) + xs.cross(o)});
      o_part += xe.cross(xs);
    }
    const Row per_vertex = c_share / static_cast<double>(curve.vertices.size());
    for (int v : curve.vertices) terms.push_back({v, per_vertex});
    const bool other_part = curve.q < count_;  // else the mesh's boundary: nothing on the other side
    for (const auto& [v, g] : terms) {
      add(v, curve.p, g);
      if (other_part) add(v, curve.q, -g);
    }
    o_share[curve.p] += o_part;
    if (other_part) o_share[curve.q] -= o_part;
  }
  for (int p = 0; p < count_; ++p)
    for (int v : junctions_) add(v, p, o_share[p] / static_cast<double>(junctions_.size()));
  G /= 6.0;
  return G;
}

std::vector<int> default_volume_parts(const Vertices& X0, const Faces& F) {
  std::vector<int> part = component_parts(F);
  if (part.empty()) return part;
  const int components = *std::max_element(part.begin(), part.end()) + 1;
  if (components == 1) return has_boundary(F) ? part : std::vector<int>{};
  const PartVolumes volumes(F, static_cast<int>(X0.rows()), part);
  const Eigen::VectorXd v = volumes.evaluate(X0, volume_reference(X0, F));
  // Flatness is a component's own property: measured against the whole model's box, a sphere of 1e-3 of it kept its
  // own volume beside the body and lost it 20 diagonals away.
  const Eigen::Matrix<double, Eigen::Dynamic, 6> box = group_boxes(X0, F, part, components);
  const Eigen::VectorXd diagonal = (box.rightCols(3) - box.leftCols(3)).rowwise().norm();
  // Components by decreasing |volume|: the largest kMaxDefaultParts - 1 keep their own; the rest, and every
  // flat one, share the part of the largest small one (or of the largest of all when none is left over).
  std::vector<int> order(static_cast<size_t>(components));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(v[a]) > std::abs(v[b]); });
  std::vector<int> target(static_cast<size_t>(components));
  for (int rank = 0; rank < components; ++rank) {
    const int c = order[rank];
    const bool flat = !(std::abs(v[c]) > kFlatPartRatio * diagonal[c] * diagonal[c] * diagonal[c]);
    target[c] = flat ? order[0] : rank < kMaxDefaultParts - 1 ? c : order[kMaxDefaultParts - 1];
  }
  for (int& p : part) p = target[p];
  compact_parts(part);
  return part;
}

double enclosed_volume(const Vertices& X, const Faces& F) {
  const std::vector<int> parts = default_volume_parts(X, F);
  const VolumeReference r = volume_reference(X, F);
  if (parts.empty()) return signed_volume(X, F, r);
  return PartVolumes(F, static_cast<int>(X.rows()), parts).evaluate(X, r).sum();
}

}  // namespace sd
