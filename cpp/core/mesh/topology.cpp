#include "core/mesh/topology.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace sd {

DisjointSets::DisjointSets(int n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }

int DisjointSets::find(int x) {
  while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
  return x;
}

void DisjointSets::unite(int a, int b) {
  a = find(a), b = find(b);
  if (a < b) parent_[b] = a;
  else if (b < a) parent_[a] = b;
}

EdgeUses::EdgeUses(const Faces& F, const std::vector<int>& faces) {
  uses_.reserve(3 * faces.size());
  for (int f : faces)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      uses_.push_back({std::min(a, b), std::max(a, b), f, a < b});
    }
  std::sort(uses_.begin(), uses_.end(),
            [](const EdgeUse& x, const EdgeUse& y) { return x.lo != y.lo ? x.lo < y.lo : x.hi < y.hi; });
  for (size_t i = 0; i < uses_.size();) {
    Edge e{uses_[i].lo, uses_[i].hi, static_cast<int>(i), 0, 0};
    for (; i < uses_.size() && uses_[i].lo == e.lo && uses_[i].hi == e.hi; ++i) {
      ++e.faces;
      e.forward += uses_[i].forward;
    }
    edges_.push_back(e);
  }
}

EdgeUses::EdgeUses(const Faces& F) : EdgeUses(F, all_faces(F)) {}

int boundary_loop_count(const EdgeUses& edges) {
  int n = 0;
  for (const Edge& e : edges.edges())
    if (e.boundary()) n = std::max(n, e.hi + 1);
  DisjointSets sets(n);
  std::vector<char> on(static_cast<size_t>(n), 0);
  for (const Edge& e : edges.edges())
    if (e.boundary()) {
      sets.unite(e.lo, e.hi);
      on[e.lo] = on[e.hi] = 1;
    }
  int loops = 0;
  for (int v = 0; v < n; ++v) loops += on[v] && sets.find(v) == v;
  return loops;
}

Components connected_components(const Faces& F, int vertex_count, const std::vector<int>& faces) {
  DisjointSets sets(vertex_count);
  for (int f : faces) {
    sets.unite(F(f, 0), F(f, 1));
    sets.unite(F(f, 0), F(f, 2));
  }
  Components out;
  out.of_face.assign(static_cast<size_t>(F.rows()), -1);
  std::vector<int> id(static_cast<size_t>(vertex_count), -1);  // per root
  for (int f : faces) {
    int& c = id[sets.find(F(f, 0))];
    if (c < 0) c = out.count++;
    out.of_face[f] = c;
  }
  return out;
}

Components connected_components(const Faces& F) {
  if (F.rows() == 0) return {};
  return connected_components(F, F.maxCoeff() + 1, all_faces(F));
}

std::vector<int> non_manifold_vertices(const Faces& F, int vertex_count, const std::vector<int>& faces) {
  // The link of each vertex as a list of opposite edges, bucketed by vertex (counting sort).
  const int n = vertex_count;
  std::vector<int> start(static_cast<size_t>(n) + 1, 0);
  for (int f : faces)
    for (int k = 0; k < 3; ++k) ++start[F(f, k) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<std::pair<int, int>> link(static_cast<size_t>(start[n]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int f : faces)
    for (int k = 0; k < 3; ++k) link[fill[F(f, k)]++] = {F(f, (k + 1) % 3), F(f, (k + 2) % 3)};
  // A vertex's fans are the connected pieces of its link.
  std::vector<int> bad, local;
  for (int v = 0; v < n; ++v) {
    if (start[v + 1] - start[v] < 2) continue;
    local.clear();
    for (int i = start[v]; i < start[v + 1]; ++i) {
      local.push_back(link[i].first);
      local.push_back(link[i].second);
    }
    std::sort(local.begin(), local.end());
    local.erase(std::unique(local.begin(), local.end()), local.end());
    auto id = [&](int u) { return static_cast<int>(std::lower_bound(local.begin(), local.end(), u) - local.begin()); };
    DisjointSets sets(static_cast<int>(local.size()));
    for (int i = start[v]; i < start[v + 1]; ++i) sets.unite(id(link[i].first), id(link[i].second));
    int fans = 0;
    for (int i = 0; i < static_cast<int>(local.size()); ++i) fans += sets.find(i) == i;
    if (fans > 1) bad.push_back(v);
  }
  return bad;
}

std::vector<std::pair<int, int>> duplicate_faces(const Faces& F, const std::vector<int>& faces) {
  std::vector<std::pair<std::array<int, 3>, int>> keys;  // (sorted vertices, face)
  keys.reserve(faces.size());
  for (int f : faces) {
    std::array<int, 3> k = {F(f, 0), F(f, 1), F(f, 2)};
    std::sort(k.begin(), k.end());
    keys.push_back({k, f});
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::pair<int, int>> duplicates;
  for (size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first) duplicates.push_back({keys[i - 1].second, keys[i].second});
  return duplicates;
}

std::vector<int> all_faces(const Faces& F) {
  std::vector<int> faces(static_cast<size_t>(F.rows()));
  std::iota(faces.begin(), faces.end(), 0);
  return faces;
}

}  // namespace sd
