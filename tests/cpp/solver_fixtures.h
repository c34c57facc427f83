// Small procedural deformation scenes shared by the solver tests (gauss_newton_test, deformer_test, ...):
// a capsule in a bar cage with two handle groups at its ends.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <functional>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/shapes.h"
#include "core/solver/solver_types.h"
#include "test_support.h"

namespace sd::test {

struct Scene {
  Mesh mesh;
  Mesh cage;
  std::vector<std::vector<int>> groups;  // [left end (fixed), right end (moved)]
  Vertices targets;                      // one row per handle vertex, groups in order
};

inline std::vector<int> vertices_where(const Mesh& mesh, const std::function<bool(const Eigen::RowVector3d&)>& pred) {
  std::vector<int> out;
  for (int i = 0; i < mesh.V.rows(); ++i)
    if (pred(mesh.V.row(i))) out.push_back(i);
  return out;
}

// A capsule of length 2 and radius 0.4 along x (a few hundred vertices) in a 4-segment bar cage (20
// vertices). The left cap (x < -1.1) stays, the right cap (x > 1.1) moves by `move`.
inline Scene capsule_scene(const Eigen::RowVector3d& move, int rings = 4, int cylinder_rings = 6, int segments = 12,
                           int cage_segments = 4) {
  Scene s;
  s.mesh = make_capsule(2.0, 0.4, rings, cylinder_rings, segments);
  s.cage = make_bar_cage(-1.6, 1.6, 0.6, 0.6, cage_segments);
  s.groups.push_back(vertices_where(s.mesh, [](const Eigen::RowVector3d& p) { return p.x() < -1.1; }));
  s.groups.push_back(vertices_where(s.mesh, [](const Eigen::RowVector3d& p) { return p.x() > 1.1; }));
  int rows = 0;
  for (const auto& g : s.groups) rows += static_cast<int>(g.size());
  s.targets.resize(rows, 3);
  int r = 0;
  for (size_t g = 0; g < s.groups.size(); ++g)
    for (int v : s.groups[g]) s.targets.row(r++) = s.mesh.V.row(v) + (g == 1 ? move : Eigen::RowVector3d::Zero());
  return s;
}

inline std::vector<int> flat_handles(const Scene& s) {
  std::vector<int> flat;
  for (const auto& g : s.groups) flat.insert(flat.end(), g.begin(), g.end());
  return flat;
}

// The capsule scene with a hole in the top of its cylinder (open) and the right end pulled.
inline Scene open_capsule_scene() {
  Scene s = test::capsule_scene({0.5, -0.3, 0.0});
  const Mesh open =
      test::drop_faces(s.mesh, [](const Eigen::RowVector3d& c) { return std::abs(c.x()) < 0.35 && c.z() > 0.25; });
  // Handles again on the open mesh (it is renumbered), the same regions and motion.
  Scene o = s;
  o.mesh = open;
  o.groups = {test::vertices_where(open, [](const Eigen::RowVector3d& p) { return p.x() < -1.1; }),
              test::vertices_where(open, [](const Eigen::RowVector3d& p) { return p.x() > 1.1; })};
  o.targets.resize(static_cast<Eigen::Index>(o.groups[0].size() + o.groups[1].size()), 3);
  int r = 0;
  for (size_t g = 0; g < 2; ++g)
    for (int v : o.groups[g])
      o.targets.row(r++) = open.V.row(v) + (g == 1 ? Eigen::RowVector3d(0.5, -0.3, 0.0) : Eigen::RowVector3d::Zero());
  return o;
}

// Three volume parts along a capsule: left end, middle, right end (by triangle centroid x).
inline std::vector<int> capsule_thirds(const Mesh& m) {
  std::vector<int> parts(static_cast<size_t>(m.F.rows()));
  for (int f = 0; f < m.F.rows(); ++f) {
    const double x = (m.V(m.F(f, 0), 0) + m.V(m.F(f, 1), 0) + m.V(m.F(f, 2), 0)) / 3.0;
    parts[f] = x < -0.5 ? 0 : (x < 0.5 ? 1 : 2);
  }
  return parts;
}

// The Gauss-Newton methods and step modes.
struct Combo {
  Method method;
  JacobianMode mode;
  const char* name;
};
inline const Combo kCombos[] = {{Method::Subspace, JacobianMode::Exact, "subspace/exact"},
                                {Method::Subspace, JacobianMode::Fast, "subspace/fast"},
                                {Method::Full, JacobianMode::Exact, "full/exact"},
                                {Method::Full, JacobianMode::Fast, "full/fast"}};

}  // namespace sd::test
