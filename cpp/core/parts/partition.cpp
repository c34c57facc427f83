#include "core/parts/partition.h"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>

#include "core/error.h"
#include "core/mesh/topology.h"

namespace sd {
namespace {

void check_part_count(long long parts, const std::string& what) {
  if (parts > kMaxVolumeParts)
    throw Error("volume parts: " + what + " " + std::to_string(parts) + " parts, more than the " +
                std::to_string(kMaxVolumeParts) + " a partition may have");
}

// owner[i] = the list holding index i, or -1; throws on too many lists, an index out of range, twice, or an
// empty list.
std::vector<int> owners(const std::vector<std::vector<int>>& lists, int size, const char* what) {
  check_part_count(static_cast<long long>(lists.size()), "the lists make");
  std::vector<int> owner(static_cast<size_t>(size), -1);
  for (size_t j = 0; j < lists.size(); ++j) {
    if (lists[j].empty()) throw Error("volume parts: list " + std::to_string(j) + " is empty");
    for (int i : lists[j]) {
      if (i < 0 || i >= size)
        throw Error("volume parts: list " + std::to_string(j) + " has " + what + " " + std::to_string(i) +
                    " outside [0, " + std::to_string(size) + ")");
      if (owner[i] >= 0)
        throw Error(std::string("volume parts: ") + what + " " + std::to_string(i) + " is in list " +
                    std::to_string(owner[i]) + " and list " + std::to_string(j));
      owner[i] = static_cast<int>(j);
    }
  }
  return owner;
}

// Gives unlisted entries (-1) the index after the lists; refuses when that extra part is one too many.
void assign_rest(std::vector<int>& owner, int lists) {
  bool rest = false;
  for (int& o : owner)
    if (o < 0) o = lists, rest = true;
  if (rest) check_part_count(lists + 1LL, "the lists and the unlisted rest make");
}

// Face adjacency across edges: for each triangle, its (up to 3) neighbours.
std::vector<std::vector<int>> face_neighbours(const Faces& F) {
  std::unordered_map<long long, int> face_of;
  const long long n = F.maxCoeff() + 1;
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) face_of[F(f, k) * n + F(f, (k + 1) % 3)] = f;
  std::vector<std::vector<int>> out(static_cast<size_t>(F.rows()));
  for (int f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const auto it = face_of.find(F(f, (k + 1) % 3) * n + F(f, k));
      if (it != face_of.end()) out[f].push_back(it->second);
    }
  return out;
}

// Face-connected pieces of each part: piece[f] = piece id, and each piece's part and size.
struct Pieces {
  std::vector<int> piece, part_of_piece, size;
};

Pieces pieces(const std::vector<int>& part, const std::vector<std::vector<int>>& adjacent) {
  Pieces p;
  p.piece.assign(part.size(), -1);
  for (size_t seed = 0; seed < part.size(); ++seed) {
    if (p.piece[seed] >= 0) continue;
    const int id = static_cast<int>(p.size.size());
    std::vector<int> stack{static_cast<int>(seed)};
    p.piece[seed] = id;
    int count = 0;
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      ++count;
      for (int g : adjacent[f])
        if (p.piece[g] < 0 && part[g] == part[seed]) {
          p.piece[g] = id;
          stack.push_back(g);
        }
    }
    p.part_of_piece.push_back(part[seed]);
    p.size.push_back(count);
  }
  return p;
}

}  // namespace

std::vector<int> component_parts(const Faces& F) { return connected_components(F).of_face; }

void connect_parts(std::vector<int>& part, const Faces& F) {
  const std::vector<std::vector<int>> adjacent = face_neighbours(F);
  for (int round = 0; round < 100; ++round) {
    const Pieces p = pieces(part, adjacent);
    std::map<int, int> largest;  // part -> its largest piece
    for (size_t id = 0; id < p.size.size(); ++id) {
      const auto it = largest.find(p.part_of_piece[id]);
      if (it == largest.end() || p.size[id] > p.size[it->second]) largest[p.part_of_piece[id]] = static_cast<int>(id);
    }
    if (largest.size() == p.size.size()) return;
    std::vector<std::map<int, int>> shared(p.size.size());  // piece -> neighbouring part -> shared edges
    for (size_t f = 0; f < part.size(); ++f)
      for (int g : adjacent[f])
        if (part[g] != part[f]) ++shared[p.piece[f]][part[g]];
    for (size_t f = 0; f < part.size(); ++f) {
      const int id = p.piece[f];
      if (largest[p.part_of_piece[id]] == id || shared[id].empty()) continue;
      const auto best = std::max_element(shared[id].begin(), shared[id].end(),
                                         [](const auto& a, const auto& b) { return a.second < b.second; });
      part[f] = best->first;
    }
  }
}

void compact_parts(std::vector<int>& part) {
  std::map<int, int> id;
  for (int p : part) id.emplace(p, 0);
  int next = 0;
  for (auto& entry : id) entry.second = next++;
  for (int& p : part) p = id[p];
}

std::vector<int> parts_from_vertex_labels(const std::vector<int>& vertex_part, const Faces& F) {
  std::vector<int> part(static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = vertex_part[F(f, 0)], b = vertex_part[F(f, 1)], c = vertex_part[F(f, 2)];
    part[f] = (a == b || a == c) ? a : (b == c ? b : std::min({a, b, c}));
  }
  return part;
}

int validate_parts(const std::vector<int>& part_of_face, int face_count) {
  if (static_cast<int>(part_of_face.size()) != face_count)
    throw Error("volume parts: " + std::to_string(part_of_face.size()) + " part indices for " +
                std::to_string(face_count) + " triangles (one per triangle expected)");
  long long highest = -1;  // K = highest + 1, in 64 bits: a part index of INT_MAX must not overflow it
  for (size_t f = 0; f < part_of_face.size(); ++f) {
    if (part_of_face[f] < 0)
      throw Error("volume parts: triangle " + std::to_string(f) + " has part " + std::to_string(part_of_face[f]));
    highest = std::max<long long>(highest, part_of_face[f]);
  }
  check_part_count(highest + 1, "the part indices ask for");
  const int count = static_cast<int>(highest + 1);
  std::vector<char> used(static_cast<size_t>(count), 0);
  for (int p : part_of_face) used[p] = 1;
  for (int p = 0; p < count; ++p)
    if (!used[p])
      throw Error("volume parts: part " + std::to_string(p) + " has no triangle (parts are numbered 0 .. K-1)");
  return count;
}

std::vector<int> parts_from_triangle_lists(const std::vector<std::vector<int>>& lists, int face_count) {
  std::vector<int> part = owners(lists, face_count, "triangle");
  assign_rest(part, static_cast<int>(lists.size()));
  return part;
}

std::vector<int> parts_from_vertex_lists(const std::vector<std::vector<int>>& lists, const Faces& F, int vertex_count) {
  std::vector<int> owner = owners(lists, vertex_count, "vertex");
  assign_rest(owner, static_cast<int>(lists.size()));
  const std::vector<int> part = parts_from_vertex_labels(owner, F);
  // A list must hold a triangle, so that part j is list j; the rest may be empty (everything listed).
  std::vector<char> used(lists.size() + 1, 0);
  for (int p : part) used[p] = 1;
  for (size_t j = 0; j < lists.size(); ++j)
    if (!used[j])
      throw Error("volume parts: vertex list " + std::to_string(j) +
                  " holds no triangle (a triangle goes to a list holding at least two of its vertices)");
  return part;
}

}  // namespace sd
