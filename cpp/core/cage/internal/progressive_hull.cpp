#include "core/cage/internal/progressive_hull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <string>
#include <vector>

#include "core/geometry/aabb_tree.h"
#include "core/error.h"
#include "core/geometry/self_intersection.h"
#include "core/mesh/volume.h"

namespace sd {
namespace {

using Vec3 = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
constexpr double kLpTol = 1e-10;
// Weight of the edge-length term in the collapse cost (relative to the added volume): orders the many
// zero-volume collapses of flat regions shortest-first so those regions coarsen evenly.
constexpr double kLengthWeight = 0.02;
// Folds sharper than this (cosine of the angle between neighbouring face normals) are refused.
constexpr double kFoldCos = -0.95;

// 2D step of the LP: minimize c . st subject to a_j . st >= b_j, |st_k| <= R (incremental, Seidel 1991).
bool solve_lp2(const std::vector<Vec2>& a, const std::vector<double>& b, const Vec2& c, double eps, double R,
               Vec2& st) {
  st = Vec2(c.x() > eps ? -R : c.x() < -eps ? R : 0.0, c.y() > eps ? -R : c.y() < -eps ? R : 0.0);
  for (size_t j = 0; j < a.size(); ++j) {
    if (a[j].dot(st) >= b[j] - kLpTol) continue;
    const double na = a[j].norm();
    if (na < 1e-12) {
      if (b[j] > kLpTol) return false;
      continue;
    }
    // The optimum moves onto the line a_j . st = b_j: a 1D problem along dir.
    const Vec2 q0 = a[j] * (b[j] / (na * na));
    const Vec2 dir(-a[j].y() / na, a[j].x() / na);
    double lo = -1e300, hi = 1e300;
    auto clip = [&](const Vec2& ak, double bk) {
      const double coef = ak.dot(dir), rhs = bk - ak.dot(q0);
      if (std::abs(coef) < 1e-12) return rhs <= kLpTol;
      if (coef > 0) lo = std::max(lo, rhs / coef);
      else hi = std::min(hi, rhs / coef);
      return true;
    };
    for (size_t k = 0; k < j; ++k)
      if (!clip(a[k], b[k])) return false;
    if (!clip(Vec2(1, 0), -R) || !clip(Vec2(-1, 0), -R) || !clip(Vec2(0, 1), -R) || !clip(Vec2(0, -1), -R))
      return false;
    if (lo > hi + kLpTol) return false;
    const double cd = c.dot(dir);
    double r = cd > eps ? lo : cd < -eps ? hi : std::clamp(0.0, lo, hi);
    if (lo > hi) r = 0.5 * (lo + hi);
    st = q0 + r * dir;
  }
  return true;
}

}  // namespace

bool solve_lp3(const std::vector<Vec3>& normals, const std::vector<double>& offsets, const Vec3& c, Vec3& x) {
  const double eps = 1e-9 * c.norm();
  for (int k = 0; k < 3; ++k) x[k] = c[k] > eps ? -1.0 : c[k] < -eps ? 1.0 : 0.0;
  std::vector<Vec2> a2;
  std::vector<double> b2;
  for (size_t i = 0; i < normals.size(); ++i) {
    const Vec3& n = normals[i];
    if (n.dot(x) >= offsets[i] - kLpTol) continue;
    // The optimum moves onto the plane n . x = d: a 2D problem in an orthonormal frame (u, w) of it.
    const Vec3 p0 = n * offsets[i];
    const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
    a2.clear();
    b2.clear();
    for (size_t j = 0; j < i; ++j) {
      a2.emplace_back(normals[j].dot(u), normals[j].dot(w));
      b2.push_back(offsets[j] - normals[j].dot(p0));
    }
    for (int k = 0; k < 3; ++k)
      for (double s : {1.0, -1.0}) {  // s x_k >= -1
        a2.emplace_back(s * u[k], s * w[k]);
        b2.push_back(-1.0 - s * p0[k]);
      }
    Vec2 st;
    if (!solve_lp2(a2, b2, Vec2(c.dot(u), c.dot(w)), eps, p0.norm() + 2.0, st)) return false;
    x = p0 + st.x() * u + st.y() * w;
  }
  for (size_t i = 0; i < normals.size(); ++i)
    if (normals[i].dot(x) < offsets[i] - 1e-7) return false;
  return x.cwiseAbs().maxCoeff() <= 1.0 + 1e-7;
}

namespace {

using Tri = std::array<int, 3>;

struct Candidate {
  double cost;
  int a, b;
  unsigned va, vb;
  Vec3 position;
  bool operator>(const Candidate& o) const { return cost > o.cost; }
};

class Hull {
 public:
  Hull(const Mesh& start, const ProgressiveHullOptions& options)
      : options_(options), V_(start.V), reference_(volume_reference(start.V, start.F).transpose()) {
    const int n = static_cast<int>(V_.rows());
    vf_.resize(n);
    refused_.resize(n);
    version_.assign(n, 0);
    vertex_alive_.assign(n, 1);
    alive_vertices_ = n;
    for (int f = 0; f < start.F.rows(); ++f) add_face({start.F(f, 0), start.F(f, 1), start.F(f, 2)});
    rebuild_index();
    if (options.obstacle && options.obstacle->F.rows() > 0)
      obstacle_tree_.build(triangle_boxes(options.obstacle->V, options.obstacle->F, options.clearance));
  }

  Mesh run(ProgressiveHullStats* stats) {
    const int start_vertices = alive_vertices_;
    const int target = std::max(options_.target_vertices, 4);
    for (int v = 0; v < static_cast<int>(V_.rows()); ++v)
      for (int w : neighbours(v))
        if (v < w) push(v, w);
    long long pops = 0;
    while (alive_vertices_ > target) {
      if (queue_.empty()) {
        // Stuck above the target: one more round with the shape-quality checks relaxed (flips allowed,
        // only near-complete folds refused); intersection checks stay.
        if (relaxed_) break;
        relaxed_ = true;
        for (int v = 0; v < static_cast<int>(V_.rows()); ++v)
          if (vertex_alive_[v])
            for (int w : neighbours(v))
              if (v < w) push(v, w);
        continue;
      }
      if (++pops % 64 == 0 && options_.progress &&
          !options_.progress(double(start_vertices - alive_vertices_) / std::max(1, start_vertices - target)))
        throw Error(ErrorCode::Cancelled, "cage generation cancelled");
      const Candidate c = queue_.top();
      queue_.pop();
      if (!vertex_alive_[c.a] || !vertex_alive_[c.b]) continue;
      if (version_[c.a] != c.va || version_[c.b] != c.vb) {
        // Stale (a neighbour collapsed since it was planned): plan again, lazily (Hoppe-style).
        push(c.a, c.b);
        continue;
      }
      if (collapse(c.a, c.b, c.position)) {
        ++stats_.collapses;
      } else {
        ++stats_.refused;
        refused_[c.a].push_back(c.b);  // retried when the neighbourhood changes
        refused_[c.b].push_back(c.a);
      }
    }
    if (stats) *stats = stats_;
    return compact();
  }

 private:
  void add_face(const Tri& t) {
    const int id = static_cast<int>(F_.size());
    F_.push_back(t);
    face_alive_.push_back(1);
    mark_.push_back(0);
    for (int k = 0; k < 3; ++k) vf_[t[k]].push_back(id);
    recent_.push_back(id);
    recent_boxes_.push_back(box(t, 0.0));
    ++alive_faces_;
  }

  double fold_cos() const { return relaxed_ ? -0.999 : kFoldCos; }
  Vec3 pos(int v) const { return V_.row(v).transpose(); }
  Vec3 normal(const Tri& t) const { return (pos(t[1]) - pos(t[0])).cross(pos(t[2]) - pos(t[0])); }
  Box3 box(const Tri& t, double margin) const {
    Box3 b;
    for (int k = 0; k < 3; ++k) b.extend(pos(t[k]));
    b.min().array() -= margin;
    b.max().array() += margin;
    return b;
  }

  void clean(int v) {
    auto& list = vf_[v];
    list.erase(std::remove_if(list.begin(), list.end(), [&](int f) { return !face_alive_[f]; }), list.end());
  }

  std::vector<int> neighbours(int v) {
    clean(v);
    std::vector<int> out;
    for (int f : vf_[v])
      for (int k = 0; k < 3; ++k)
        if (F_[f][k] != v) out.push_back(F_[f][k]);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  // Faces around a or b (the star of the edge), each once.
  std::vector<int> star(int a, int b) {
    clean(a);
    clean(b);
    std::vector<int> s = vf_[a];
    s.insert(s.end(), vf_[b].begin(), vf_[b].end());
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    return s;
  }

  static bool has(const Tri& t, int v) { return t[0] == v || t[1] == v || t[2] == v; }

  // New fan after merging b into a (faces holding both vanish; b is renamed a).
  std::vector<Tri> fan(const std::vector<int>& s, int a, int b) const {
    std::vector<Tri> out;
    for (int f : s) {
      Tri t = F_[f];
      if (has(t, a) && has(t, b)) continue;
      for (int& x : t)
        if (x == b) x = a;
      out.push_back(t);
    }
    return out;
  }

  // Plans the collapse of (a, b): LP position and cost. False when the LP is infeasible.
  bool plan(int a, int b, Vec3& position, double& cost) {
    const std::vector<int> s = star(a, b);
    const Vec3 m = 0.5 * (pos(a) + pos(b));
    double scale = 0;
    for (int f : s)
      for (int k = 0; k < 3; ++k) scale = std::max(scale, (pos(F_[f][k]) - m).norm());
    if (!(scale > 0)) return false;
    std::vector<Vec3> normals;
    std::vector<double> offsets;
    // The volumes about the hull's reference point, not the origin: the star and the new fan share their rim, so
    // the change is that of a closed surface, the same about any point, but about the origin a cage far from it
    // lost it to cancellation (volume.h).
    double old_volume = 0;
    for (int f : s) {
      const Tri& t = F_[f];
      old_volume += (pos(t[0]) - reference_).cross(pos(t[1]) - reference_).dot(pos(t[2]) - reference_);
      Vec3 n = normal(t);
      const double length = n.norm();
      if (!(length > 1e-14 * scale * scale)) continue;
      n /= length;
      normals.push_back(n);
      offsets.push_back(n.dot(pos(t[0]) - m) / scale);
    }
    Vec3 c = Vec3::Zero();  // new volume = (v - o) . c (+ unchanged faces): sum of x cross y over the new fan
    for (const Tri& t : fan(s, a, b)) {
      int k = 0;
      while (t[k] != a) ++k;
      c += (pos(t[(k + 1) % 3]) - reference_).cross(pos(t[(k + 2) % 3]) - reference_);
    }
    Vec3 x;
    const double cn = c.norm();
    if (!solve_lp3(normals, offsets, cn > 0 ? Vec3(c / cn) : Vec3::Zero(), x)) return false;
    position = m + scale * x;
    const double added = ((position - reference_).dot(c) - old_volume) / 6.0;
    cost = added + kLengthWeight * std::pow((pos(a) - pos(b)).norm(), 3);
    return true;
  }

  void push(int a, int b) {
    if (a > b) std::swap(a, b);
    Candidate c;
    if (!plan(a, b, c.position, c.cost)) return;
    c.a = a;
    c.b = b;
    c.va = version_[a];
    c.vb = version_[b];
    queue_.push(c);
  }

  bool topology_allows(int a, int b, const std::vector<int>& na, const std::vector<int>& nb,
                       const std::vector<int>& s) {
    std::vector<int> common;
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    std::vector<int> opposite;
    for (int f : s)
      if (has(F_[f], a) && has(F_[f], b))
        for (int x : F_[f])
          if (x != a && x != b) opposite.push_back(x);
    std::sort(opposite.begin(), opposite.end());
    if (opposite.size() != 2 || common != opposite) return false;  // link condition
    if (na.size() + nb.size() - 4 < 3) return false;
    for (int x : opposite)
      if (neighbours(x).size() < 4) return false;
    return true;
  }

  // Geometric checks with a already moved to its new position. `fresh` are the new faces.
  bool geometry_allows(const std::vector<Tri>& fresh, const std::vector<Vec3>& before, double scale) {
    std::vector<Vec3> normals;
    for (size_t i = 0; i < fresh.size(); ++i) {
      Vec3 n = normal(fresh[i]);
      const double length = n.norm();
      if (!(length > 1e-10 * scale * scale)) return false;  // degenerate
      n /= length;
      if (!relaxed_ && n.dot(before[i]) <= 0) return false;  // flipped
      normals.push_back(n);
    }
    // Folds: across every edge of a new face.
    for (size_t i = 0; i < fresh.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const int x = fresh[i][k], y = fresh[i][(k + 1) % 3];
        bool found = false;
        for (size_t j = 0; j < fresh.size() && !found; ++j)
          if (j != i && has(fresh[j], x) && has(fresh[j], y)) {
            found = true;
            if (normals[i].dot(normals[j]) < fold_cos()) return false;
          }
        if (found) continue;
        for (int f : vf_[x])
          if (face_alive_[f] && mark_[f] != stamp_ && has(F_[f], y)) {
            if (normals[i].dot(normal(F_[f]).normalized()) < fold_cos()) return false;
            break;
          }
      }
    const double tol = options_.tolerance;
    for (size_t i = 0; i < fresh.size(); ++i) {
      const Eigen::Vector3i fi(fresh[i][0], fresh[i][1], fresh[i][2]);
      for (size_t j = i + 1; j < fresh.size(); ++j)
        if (faces_intersect(V_, fi, Eigen::Vector3i(fresh[j][0], fresh[j][1], fresh[j][2]), tol)) return false;
      const Box3 query = box(fresh[i], tol);
      auto hits = [&](int f) {
        if (!face_alive_[f] || mark_[f] == stamp_) return false;
        return faces_intersect(V_, fi, Eigen::Vector3i(F_[f][0], F_[f][1], F_[f][2]), tol);
      };
      bool clear = tree_.overlapping(query, [&](int item) { return !hits(tree_faces_[item]); });
      if (!clear) return false;
      for (size_t r = 0; r < recent_.size(); ++r)
        if (recent_boxes_[r].intersects(query) && hits(recent_[r])) return false;
      if (options_.obstacle) {
        const Mesh& o = *options_.obstacle;
        const Vec3 p0 = pos(fresh[i][0]), p1 = pos(fresh[i][1]), p2 = pos(fresh[i][2]);
        const Box3 reach = box(fresh[i], options_.clearance);
        clear = obstacle_tree_.overlapping(reach, [&](int g) {
          return !triangles_intersect(p0, p1, p2, o.V.row(o.F(g, 0)).transpose(), o.V.row(o.F(g, 1)).transpose(),
                                      o.V.row(o.F(g, 2)).transpose(), options_.clearance);
        });
        if (!clear) return false;
      }
    }
    return true;
  }

  bool collapse(int a, int b, const Vec3& position) {
    const std::vector<int> s = star(a, b);
    const std::vector<int> na = neighbours(a), nb = neighbours(b);
    if (!topology_allows(a, b, na, nb, s)) return false;
    ++stamp_;
    for (int f : s) mark_[f] = stamp_;
    const std::vector<Tri> fresh = fan(s, a, b);
    std::vector<Vec3> before;  // each new face's normal before the move
    for (const Tri& t : fresh) {
      Tri original = t;
      for (int f : s) {
        // The star face this new face came from: same vertices once b is renamed to a.
        Tri renamed = F_[f];
        for (int& x : renamed)
          if (x == b) x = a;
        if (renamed == t) {
          original = F_[f];
          break;
        }
      }
      before.push_back(normal(original));
    }
    double scale = (pos(a) - pos(b)).norm();
    for (int f : s)
      for (int k = 0; k < 3; ++k) scale = std::max(scale, (pos(F_[f][k]) - position).norm());
    const Eigen::RowVector3d saved = V_.row(a);
    V_.row(a) = position.transpose();
    if (!geometry_allows(fresh, before, scale)) {
      V_.row(a) = saved;
      return false;
    }
    for (int f : s) {
      face_alive_[f] = 0;
      --alive_faces_;
    }
    vf_[a].clear();
    vf_[b].clear();
    vertex_alive_[b] = 0;
    --alive_vertices_;
    for (const Tri& t : fresh) add_face(t);
    std::vector<int> ring = na;
    ring.insert(ring.end(), nb.begin(), nb.end());
    ring.erase(std::remove_if(ring.begin(), ring.end(), [&](int x) { return x == a || x == b; }), ring.end());
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
    ++version_[a];
    for (int x : ring) ++version_[x];
    // The edges of the new vertex are planned now; the other edges around it still have queue entries,
    // now stale, which are planned again when they come up. Edges refused before get another chance.
    std::vector<std::pair<int, int>> edges;
    for (int y : neighbours(a)) edges.push_back({std::min(a, y), std::max(a, y)});
    ring.push_back(a);
    ring.push_back(b);
    for (int x : ring) {
      for (int y : refused_[x])
        if (vertex_alive_[x] && vertex_alive_[y]) edges.push_back({std::min(x, y), std::max(x, y)});
      refused_[x].clear();
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [x, y] : edges) push(x, y);
    if (static_cast<int>(recent_.size()) > std::max(64, alive_faces_ / 8)) rebuild_index();
    return true;
  }

  void rebuild_index() {
    std::vector<Box3> boxes;
    tree_faces_.clear();
    for (int f = 0; f < static_cast<int>(F_.size()); ++f)
      if (face_alive_[f]) {
        boxes.push_back(box(F_[f], options_.tolerance));
        tree_faces_.push_back(f);
      }
    tree_.build(std::move(boxes));
    recent_.clear();
    recent_boxes_.clear();
  }

  Mesh compact() const {
    std::vector<int> id(V_.rows(), -1);
    int count = 0;
    for (int v = 0; v < static_cast<int>(V_.rows()); ++v)
      if (vertex_alive_[v]) id[v] = count++;
    Mesh out;
    out.V.resize(count, 3);
    for (int v = 0; v < static_cast<int>(V_.rows()); ++v)
      if (id[v] >= 0) out.V.row(id[v]) = V_.row(v);
    out.F.resize(alive_faces_, 3);
    int row = 0;
    for (size_t f = 0; f < F_.size(); ++f)
      if (face_alive_[f]) out.F.row(row++) << id[F_[f][0]], id[F_[f][1]], id[F_[f][2]];
    return out;
  }

  const ProgressiveHullOptions& options_;
  Vertices V_;
  Vec3 reference_;  // the start's volume_reference: the collapses' volume changes are summed about it
  std::vector<Tri> F_;
  std::vector<char> face_alive_;
  std::vector<int> mark_;
  int stamp_ = 0;
  bool relaxed_ = false;
  std::vector<std::vector<int>> vf_;
  std::vector<std::vector<int>> refused_;  // per vertex: partners of refused collapses
  std::vector<unsigned> version_;
  std::vector<char> vertex_alive_;
  int alive_vertices_ = 0, alive_faces_ = 0;
  AabbTree tree_, obstacle_tree_;
  std::vector<int> tree_faces_;
  std::vector<int> recent_;  // faces added since the tree was built, and their boxes
  std::vector<Box3> recent_boxes_;
  std::priority_queue<Candidate, std::vector<Candidate>, std::greater<Candidate>> queue_;
  ProgressiveHullStats stats_;
};

}  // namespace

Mesh progressive_hull(const Mesh& start, const ProgressiveHullOptions& options, ProgressiveHullStats* stats) {
  if (start.V.rows() < 4 || start.F.rows() < 4)
    throw Error(ErrorCode::InvalidMesh, "progressive hull: the start mesh has " + std::to_string(start.V.rows()) +
                                            " vertices and " + std::to_string(start.F.rows()) +
                                            " faces; a closed mesh needs at least 4 of each");
  Hull hull(start, options);
  return hull.run(stats);
}

}  // namespace sd
