#include "core/parts/partition.h"

#include <algorithm>
#include <string>

#include "core/error.h"

namespace sd {
namespace {

// owner[i] = the list holding index i, or -1; throws on an index out of range, twice, or an empty list.
std::vector<int> owners(const std::vector<std::vector<int>>& lists, int size, const char* what) {
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

// Gives unlisted entries (-1) the index after the lists.
void assign_rest(std::vector<int>& owner, int lists) {
  for (int& o : owner)
    if (o < 0) o = lists;
}

}  // namespace

int validate_parts(const std::vector<int>& part_of_face, int face_count) {
  if (static_cast<int>(part_of_face.size()) != face_count)
    throw Error("volume parts: " + std::to_string(part_of_face.size()) + " part indices for " +
                std::to_string(face_count) + " triangles (one per triangle expected)");
  int count = 0;
  for (size_t f = 0; f < part_of_face.size(); ++f) {
    if (part_of_face[f] < 0)
      throw Error("volume parts: triangle " + std::to_string(f) + " has part " + std::to_string(part_of_face[f]));
    count = std::max(count, part_of_face[f] + 1);
  }
  std::vector<char> used(static_cast<size_t>(count), 0);
  for (int p : part_of_face) used[p] = 1;
  for (int p = 0; p < count; ++p)
    if (!used[p]) throw Error("volume parts: part " + std::to_string(p) + " has no triangle (parts are numbered 0 .. K-1)");
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
  std::vector<int> part(static_cast<size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = owner[F(f, 0)], b = owner[F(f, 1)], c = owner[F(f, 2)];
    part[f] = (a == b || a == c) ? a : (b == c ? b : std::min({a, b, c}));
  }
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
