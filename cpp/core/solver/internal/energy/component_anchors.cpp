#include "core/solver/internal/energy/component_anchors.h"

#include <algorithm>

#include "core/parts/partition.h"

namespace sd {
namespace {

// The component's three anchor vertices: spread out so that they pin its rotations as well as its translation.
std::vector<int> spread_triple(const Vertices& X0, const std::vector<int>& vertices) {
  const int a = vertices.front();
  const auto farthest = [&](auto distance) {
    int best = a;
    double best_d = 0.0;
    for (int v : vertices)
      if (const double d = distance(v); d > best_d) {
        best_d = d;
        best = v;
      }
    return best;
  };
  const int b = farthest([&](int v) { return (X0.row(v) - X0.row(a)).squaredNorm(); });
  if (b == a) return {a};
  const Eigen::RowVector3d ab = X0.row(b) - X0.row(a);
  const int c = farthest([&](int v) { return ab.cross(X0.row(v) - X0.row(a)).squaredNorm(); });
  return c == a ? std::vector<int>{a, b} : std::vector<int>{a, b, c};
}

}  // namespace

std::vector<std::vector<int>> component_anchors(const Vertices& X0, const Faces& F, const std::vector<int>& handles) {
  const std::vector<int> part_of_face = component_parts(F);
  if (part_of_face.empty()) return {};
  const int components = *std::max_element(part_of_face.begin(), part_of_face.end()) + 1;
  if (components < 2) return {};  // one component: the handles hold it
  std::vector<int> component(static_cast<size_t>(X0.rows()), -1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) component[static_cast<size_t>(F(f, k))] = part_of_face[static_cast<size_t>(f)];
  std::vector<char> held(static_cast<size_t>(components), 0);
  for (int v : handles)
    if (component[static_cast<size_t>(v)] >= 0) held[static_cast<size_t>(component[static_cast<size_t>(v)])] = 1;
  std::vector<std::vector<int>> members(static_cast<size_t>(components));
  for (int v = 0; v < static_cast<int>(X0.rows()); ++v)
    if (component[static_cast<size_t>(v)] >= 0)
      members[static_cast<size_t>(component[static_cast<size_t>(v)])].push_back(v);
  std::vector<std::vector<int>> out;
  for (int c = 0; c < components; ++c)
    if (!held[static_cast<size_t>(c)] && !members[static_cast<size_t>(c)].empty())
      out.push_back(spread_triple(X0, members[static_cast<size_t>(c)]));
  return out;
}

}  // namespace sd
