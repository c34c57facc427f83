// The topology of a triangle list: the facts that do not depend on positions, found once here for the checks
// (mesh_check.h, which words them), the vertex layout (mesh_layout.h: welding, non-manifold splits) and the
// volume parts (parts/partition.h: components).
//   - DisjointSets: union-find whose root is the smallest element of its set;
//   - EdgeUses: the faces' edges, undirected and sorted, so the faces of one edge sit together, and each edge's
//     class (boundary, manifold, non-manifold, inconsistently oriented);
//   - connected components of faces through shared vertices;
//   - boundary loops: the connected pieces of the boundary edges;
//   - non-manifold vertices: those whose faces form several fans;
//   - duplicate faces: two faces on the same three vertices.
// Functions that take `faces` consider only those rows of F (the checks leave out faces with out-of-range
// indices, and from the edges also those that repeat an index); their indices must be in [0, vertex_count).
#pragma once

#include <utility>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// Union-find over 0 .. n-1 with path halving. The root of a set is its smallest element, so "find(x) == x"
// picks the lowest index of each set (the file vertex that names a welded point, say).
class DisjointSets {
 public:
  explicit DisjointSets(int n);
  int find(int x);
  void unite(int a, int b);
  int size() const { return static_cast<int>(parent_.size()); }

 private:
  std::vector<int> parent_;
};

// One use of an undirected edge by a face: the edge (lo < hi), the face, and whether the face walks lo -> hi.
struct EdgeUse {
  int lo, hi, face;
  bool forward;
};

// One undirected edge and how its faces use it.
struct Edge {
  int lo, hi;   // lo < hi
  int first;    // its uses: EdgeUses::uses()[first .. first + faces)
  int faces;    // how many faces use it
  int forward;  // how many of them walk it lo -> hi
  bool boundary() const { return faces == 1; }
  bool non_manifold() const { return faces > 2; }
  // Two faces walking it the same way: their orientations disagree.
  bool misoriented() const { return faces == 2 && forward != 1; }
};

// The three edge uses of each face, sorted by edge (lo, then hi), and the distinct edges in that order. A face
// that repeats an index uses a degenerate edge (lo == hi) and belongs in no `faces` list.
class EdgeUses {
 public:
  EdgeUses(const Faces& F, const std::vector<int>& faces);
  explicit EdgeUses(const Faces& F);  // every face
  const std::vector<EdgeUse>& uses() const { return uses_; }
  const std::vector<Edge>& edges() const { return edges_; }
  const EdgeUse* uses_of(const Edge& e) const { return uses_.data() + e.first; }

 private:
  std::vector<EdgeUse> uses_;
  std::vector<Edge> edges_;
};

// The number of boundary loops: the connected pieces of the boundary edges (edges of one face). Two holes
// that meet at a vertex make one piece.
int boundary_loop_count(const EdgeUses& edges);

// Connected components of faces joined through shared vertices (for an edge- and vertex-manifold mesh the
// same as through shared edges), numbered 0 .. count-1 in the order of their first face.
struct Components {
  int count = 0;
  std::vector<int> of_face;  // one per row of F; -1 for a face not considered
};
Components connected_components(const Faces& F, int vertex_count, const std::vector<int>& faces);
Components connected_components(const Faces& F);  // every face (vertex count: the largest index + 1)

// Vertices whose link (the opposite edges of their faces) falls apart into several fans, e.g. the shared corner
// of two cones touching at their tips; in increasing order.
std::vector<int> non_manifold_vertices(const Faces& F, int vertex_count, const std::vector<int>& faces);

// Faces on the same three vertices (in either orientation) as (one face, the next such face) in order of
// their sorted vertices, then face index: three copies make two pairs.
std::vector<std::pair<int, int>> duplicate_faces(const Faces& F, const std::vector<int>& faces);

// 0 .. F.rows() - 1: every face, for the functions above.
std::vector<int> all_faces(const Faces& F);

}  // namespace sd
