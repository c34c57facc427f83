#include "core/mesh/vertex_normals.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/parallel/parallel_for.h"

namespace sd {

VertexNormals::VertexNormals(int n, const Faces& faces, std::vector<int> group, std::vector<float> fallback)
    : faces_(faces), group_(std::move(group)), fallback_(std::move(fallback)) {
  if (faces_.size() && (faces_.minCoeff() < 0 || faces_.maxCoeff() >= n))
    throw Error("normals: a triangle names a vertex the mesh does not have");
  if (group_.empty()) {
    group_.resize(static_cast<size_t>(n));
    for (int v = 0; v < n; ++v) group_[static_cast<size_t>(v)] = v;
  }
  if (static_cast<int>(group_.size()) != n)
    throw Error("normal groups: " + std::to_string(group_.size()) + " entries for " + std::to_string(n) + " vertices");
  if (!fallback_.empty() && fallback_.size() != 3 * group_.size())
    throw Error("rest normals: " + std::to_string(fallback_.size()) + " numbers for " + std::to_string(group_.size()) +
                " vertices (expected 3 per vertex)");
  // n vertices make at most n groups; a larger id would size the per-group arrays from it (2^31 - 1 overflowed
  // g + 1, 1e9 asked for gigabytes).
  int groups = 0;
  for (size_t v = 0; v < group_.size(); ++v) {
    const int g = group_[v];
    if (g < 0 || g >= n)
      throw Error("normal groups: vertex " + std::to_string(v) + " has group " + std::to_string(g) + ", outside [0, " +
                  std::to_string(n) + ")");
    groups = std::max(groups, g + 1);
  }
  // Counting sort of the corners by group: each group's triangles in triangle order.
  offsets_.assign(static_cast<size_t>(groups) + 1, 0);
  for (Eigen::Index t = 0; t < faces_.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++offsets_[static_cast<size_t>(group_[static_cast<size_t>(faces_(t, k))]) + 1];
  for (size_t g = 0; g + 1 < offsets_.size(); ++g) offsets_[g + 1] += offsets_[g];
  corners_.resize(static_cast<size_t>(offsets_.back()));
  std::vector<int> next(offsets_.begin(), offsets_.end() - 1);
  for (Eigen::Index t = 0; t < faces_.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      corners_[static_cast<size_t>(next[static_cast<size_t>(group_[static_cast<size_t>(faces_(t, k))])]++)] =
          static_cast<int>(t);
  group_sums_.resize(groups, 3);
}

void VertexNormals::compute(const Vertices& X, std::vector<float>& out) const {
  const int n = static_cast<int>(group_.size());
  if (X.rows() != n)
    throw Error("normals: " + std::to_string(X.rows()) + " positions for " + std::to_string(n) + " vertices");
  face_normals_.resize(faces_.rows(), 3);
  parallel::parallel_for(0, static_cast<int>(faces_.rows()), 4096, [&](int lo, int hi) {
    for (int t = lo; t < hi; ++t) {
      const Eigen::RowVector3d a = X.row(faces_(t, 0));
      face_normals_.row(t) = (X.row(faces_(t, 1)) - a).cross(X.row(faces_(t, 2)) - a);
    }
  });
  parallel::parallel_for(0, static_cast<int>(group_sums_.rows()), 4096, [&](int lo, int hi) {
    for (int g = lo; g < hi; ++g) {
      Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
      for (int c = offsets_[static_cast<size_t>(g)]; c < offsets_[static_cast<size_t>(g) + 1]; ++c)
        sum += face_normals_.row(corners_[static_cast<size_t>(c)]);
      group_sums_.row(g) = sum;
    }
  });
  out.resize(3 * static_cast<size_t>(n));
  parallel::parallel_for(0, n, 4096, [&](int lo, int hi) {
    for (int v = lo; v < hi; ++v) {
      const auto sum = group_sums_.row(group_[static_cast<size_t>(v)]);
      const double length = sum.norm();
      float* o = &out[3 * static_cast<size_t>(v)];
      if (length > 0) {
        for (int d = 0; d < 3; ++d) o[d] = static_cast<float>(sum[d] / length);
      } else if (!fallback_.empty() && !std::isnan(fallback_[3 * static_cast<size_t>(v)])) {
        for (int d = 0; d < 3; ++d) o[d] = fallback_[3 * static_cast<size_t>(v) + d];
      } else {
        o[0] = o[1] = o[2] = 0.0f;
      }
    }
  });
}

}  // namespace sd
