#include "core/basis/internal/cage_grid.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace sd {
namespace {

// The origin's shift below the box, in cells per axis: a cell of margin plus fractions no round coordinate
// shares, so nodes do not line up with axis-aligned cage faces.
const double kShift[3] = {1.1372, 1.2614, 1.3895};

// Sign of the orientation of p against the directed edge u -> v in the line's cross-section (coordinates b, c),
// with p moved by (eps, eps^2) when it lies on the edge's line (simulation of simplicity): never 0 for u != v.
int orientation(const double u[2], const double v[2], const double p[2]) {
  const double e = (v[0] - u[0]) * (p[1] - u[1]) - (v[1] - u[1]) * (p[0] - u[0]);
  if (e != 0) return e > 0 ? 1 : -1;
  if (v[1] != u[1]) return v[1] > u[1] ? -1 : 1;  // the eps term: -(v_c - u_c)
  return v[0] > u[0] ? 1 : -1;                    // the eps^2 term: (v_b - u_b)
}

}  // namespace

Eigen::Array3i CageGrid::node_counts(const Mesh& cage, double spacing) {
  const Eigen::Vector3d lo = cage.V.colwise().minCoeff().transpose(), hi = cage.V.colwise().maxCoeff().transpose();
  Eigen::Array3i n;
  for (int a = 0; a < 3; ++a) n[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / spacing + kShift[a])) + 2;
  return n;
}

CageGrid::CageGrid(const Mesh& cage, double spacing) : h_(spacing) {
  n_ = node_counts(cage, spacing);
  const Eigen::Vector3d lo = cage.V.colwise().minCoeff().transpose();
  for (int a = 0; a < 3; ++a) origin_[a] = lo[a] - kShift[a] * spacing;
  for (int axis = 0; axis < 3; ++axis) find_crossings(cage, axis);
  classify();
}

long long CageGrid::line(int axis, int i, int j, int k) const {
  const int index[3] = {i, j, k};
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  return static_cast<long long>(index[c]) * n_[b] + index[b];
}

// Every crossing of the lines along `axis` with the cage's triangles: each triangle visits the lines through its
// bounding box in the cross-section and keeps those inside it.
void CageGrid::find_crossings(const Mesh& cage, int axis) {
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  std::vector<std::pair<long long, GridCrossing>> found;
  for (int f = 0; f < cage.F.rows(); ++f) {
    const int v[3] = {cage.F(f, 0), cage.F(f, 1), cage.F(f, 2)};
    double q[3][2];
    for (int k = 0; k < 3; ++k) {
      q[k][0] = cage.V(v[k], b);
      q[k][1] = cage.V(v[k], c);
    }
    const double area = (q[1][0] - q[0][0]) * (q[2][1] - q[0][1]) - (q[1][1] - q[0][1]) * (q[2][0] - q[0][0]);
    if (area == 0) continue;  // parallel to the lines
    const int side = area > 0 ? 1 : -1;
    auto range = [&](int along, int coordinate) {
      double lo = q[0][coordinate], hi = lo;
      for (int k = 1; k < 3; ++k) {
        lo = std::min(lo, q[k][coordinate]);
        hi = std::max(hi, q[k][coordinate]);
      }
      const int first = std::max(0, static_cast<int>(std::ceil((lo - origin_[along]) / h_)));
      const int last = std::min(n_[along] - 1, static_cast<int>(std::floor((hi - origin_[along]) / h_)));
      return std::make_pair(first, last);
    };
    const auto [b0, b1] = range(b, 0);
    const auto [c0, c1] = range(c, 1);
    for (int jc = c0; jc <= c1; ++jc)
      for (int jb = b0; jb <= b1; ++jb) {
        const double p[2] = {origin_[b] + h_ * jb, origin_[c] + h_ * jc};
        // Each edge is tested in one direction for both triangles that share it (lower vertex index first),
        // so they agree on which side p is.
        bool in = true;
        for (int k = 0; k < 3 && in; ++k) {
          const int s = (k + 1) % 3, t = (k + 2) % 3;  // the edge opposite corner k, s -> t in the triangle
          const bool forward = v[s] < v[t];
          const int o = forward ? orientation(q[s], q[t], p) : -orientation(q[t], q[s], p);
          in = o == side;
        }
        if (!in) continue;
        GridCrossing crossing;
        crossing.face = f;
        double total = 0;
        for (int k = 0; k < 3; ++k) {
          const double* s = q[(k + 1) % 3];
          const double* t = q[(k + 2) % 3];
          const double e = (t[0] - s[0]) * (p[1] - s[1]) - (t[1] - s[1]) * (p[0] - s[0]);
          crossing.bary[k] = std::max(0.0, e / area);
          total += crossing.bary[k];
        }
        crossing.at = 0;
        for (int k = 0; k < 3; ++k) {
          crossing.bary[k] /= total;
          crossing.at += crossing.bary[k] * cage.V(v[k], axis);
        }
        const int index[3] = {axis == 0 ? 0 : (b == 0 ? jb : jc), axis == 1 ? 0 : (b == 1 ? jb : jc),
                              axis == 2 ? 0 : (b == 2 ? jb : jc)};
        found.push_back({line(axis, index[0], index[1], index[2]), crossing});
      }
  }
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
    return x.first != y.first           ? x.first < y.first
           : x.second.at != y.second.at ? x.second.at < y.second.at
                                        : x.second.face < y.second.face;
  });
  const long long lines = static_cast<long long>(n_[b]) * n_[c];
  offsets_[axis].assign(static_cast<size_t>(lines + 1), 0);
  crossings_[axis].resize(found.size());
  for (size_t k = 0; k < found.size(); ++k) {
    crossings_[axis][k] = found[k].second;
    ++offsets_[axis][static_cast<size_t>(found[k].first + 1)];
  }
  for (long long l = 0; l < lines; ++l) offsets_[axis][l + 1] += offsets_[axis][l];
}

void CageGrid::classify() {
  inside_.assign(static_cast<size_t>(n_[0]) * n_[1] * n_[2], 0);
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j) {
      const long long l = line(0, 0, j, k);
      const GridCrossing* c = crossings_[0].data() + offsets_[0][l];
      const GridCrossing* end = crossings_[0].data() + offsets_[0][l + 1];
      bool in = false;
      for (int i = 0; i < n_[0]; ++i) {
        const double x = origin_[0] + h_ * i;
        for (; c != end && c->at < x; ++c) in = !in;
        inside_[static_cast<size_t>(node(i, j, k))] = in;
      }
    }
}

void CageGrid::crossings_between(int axis, int i, int j, int k, int step, std::vector<const GridCrossing*>& out) const {
  out.clear();
  const int index[3] = {i, j, k};
  const double from = origin_[axis] + h_ * index[axis], to = from + step * h_;
  const long long l = line(axis, i, j, k);
  const GridCrossing* begin = crossings_[axis].data() + offsets_[axis][l];
  const GridCrossing* end = crossings_[axis].data() + offsets_[axis][l + 1];
  if (step > 0) {
    for (const GridCrossing* c = begin; c != end; ++c)
      if (c->at > from && c->at < to) out.push_back(c);
  } else {
    for (const GridCrossing* c = end; c != begin;) {
      --c;
      if (c->at < from && c->at > to) out.push_back(c);
    }
  }
}

}  // namespace sd
