// The file's vertex layout and the solver's topology, and the maps between them (docs/library.md, "Vertex
// layout").
//
// Files split vertices: a UV or normal seam, a flat-shaded export or non-indexed geometry gives one vertex per
// corner it needs, so the triangles of a closed model meet at copies and look like an open mesh with many
// components. The solver needs the surface itself. A MeshLayout is built once from the mesh as read (the file
// layout) and gives the solver mesh:
//   1. welding: vertices within `weld_tolerance` x the bounding-box diagonal of each other are one point
//      (transitively); the lowest file index represents them;
//   2. faces whose corners weld together (a zero-length edge, or a repeated index) are dropped: they have no
//      area to deform;
//   3. vertices no remaining face uses are dropped; they are carried along instead (below);
//   4. non-manifold vertices and edges are split where that is well defined: around an edge with more than two
//      faces, the faces are paired with their neighbour in angular order that closes a solid wedge (orientation
//      alternates around such an edge when it is well defined); a vertex then gets one copy per fan of faces
//      joined across its manifold or paired edges. Edges that cannot be paired stay as they are (the check
//      names them: non_manifold_edge).
// Everything is kept for display and export: to_file() gives positions in the file layout (welded copies take
// their solver vertex's position, a split vertex the mean of its copies), and an unreferenced vertex follows
// the nearest solver triangle rigidly: barycentric coordinates of its closest point plus its offset in the
// triangle's orthonormal frame (edge, normal x edge, normal), so it moves with the surface as W moves the rest
// and keeps its distance to it.
// Handles, volume parts and messages given in file numbering are mapped here too.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct LayoutOptions {
  // Relative to the bounding-box diagonal. 1e-6: far above float32 round-off of positions written from the
  // same value (exporters copy the bits; quantised and text formats round both copies alike) and far below
  // any real edge (a million-triangle model's edges are ~1e-3 of its diagonal). 0: only equal positions.
  double weld_tolerance = 1e-6;
};

struct LayoutStats {
  int file_vertices = 0;
  int file_faces = 0;
  int solver_vertices = 0;
  int solver_faces = 0;
  int welded = 0;           // referenced file vertices merged into another: file's referenced - distinct points
  int unreferenced = 0;     // file vertices no solver face uses (carried along)
  int collapsed_faces = 0;  // file faces dropped because corners welded together
  int split_vertices = 0;   // solver vertices added by splitting non-manifold vertices and edges
  int paired_edges = 0;     // non-manifold edges split by pairing their faces
};

// Handle groups given in file numbering, in solver numbering: the solver copies of each file vertex (welded
// duplicates once), and for each solver handle row the row of the file's targets it takes.
struct HandleMap {
  std::vector<std::vector<int>> groups;
  std::vector<int> file_row;
  int file_rows = 0;
};

// The file index that names a solver vertex or face in messages (check_mesh).
struct IndexNames {
  std::vector<int> vertex;
  std::vector<int> face;
};

class MeshLayout {
 public:
  MeshLayout() = default;
  // Builds the solver mesh of `file`. A mesh with out-of-range indices or non-finite coordinates cannot be
  // welded meaningfully: its layout is the identity (the check then names those errors).
  explicit MeshLayout(const Mesh& file, const LayoutOptions& options = {});

  const Mesh& mesh() const { return solver_; }  // the solver mesh
  const LayoutStats& stats() const { return stats_; }
  bool identity() const { return identity_; }
  int file_vertex_count() const { return stats_.file_vertices; }
  int file_face_count() const { return stats_.file_faces; }

  // The solver copies of file vertex v (none when unreferenced, several when split).
  std::vector<int> solver_vertices(int file_vertex) const;
  // The file vertex that names solver vertex s (the lowest index of its welded points).
  int file_vertex(int solver_vertex) const { return file_of_solver_[solver_vertex]; }
  // Solver face of file face f, -1 when it collapsed; and the file face of solver face s.
  int solver_face(int file_face) const { return solver_face_of_file_[file_face]; }
  int file_face(int solver_face) const { return file_face_of_solver_[solver_face]; }
  // One solver vertex per file vertex (its first copy), -1 for the unreferenced: the layout as data.
  const std::vector<int>& solver_of_file() const { return solver_of_file_; }
  IndexNames names() const { return {file_of_solver_, file_face_of_solver_}; }

  // Positions in the file layout (#file vertices by 3) from solver positions X (#solver vertices by 3).
  Vertices to_file(const Vertices& X) const;
  // One value per solver vertex (a column of W, say) in the file layout: copies of a point take its value, a
  // split vertex the mean of its copies, a carried vertex the value at its closest point (barycentric).
  Eigen::VectorXd values_to_file(const Eigen::VectorXd& values) const;
  // Throws sd::Error naming the group and file vertex: an unreferenced vertex (it has no solver vertex to
  // hold), or one point in two groups (through welding).
  HandleMap map_handles(const std::vector<std::vector<int>>& file_groups) const;
  // Solver targets from the file's (one row per file handle vertex, groups in order).
  Vertices solver_targets(const HandleMap& map, const Vertices& file_targets) const;
  // One part per solver face from one per file face (parts no solver face keeps are dropped and the rest
  // renumbered), and back (a collapsed file face takes the part of a solver face around its first corner).
  std::vector<int> solver_face_parts(const std::vector<int>& file_parts) const;
  std::vector<int> file_face_parts(const std::vector<int>& solver_parts) const;

 private:
  struct Attachment {
    int face = -1;            // solver face (-1: none, the solver mesh has no faces; offset is the position)
    Eigen::Vector3d weights;  // barycentric coordinates of the closest point
    Eigen::Vector3d offset;   // the vertex minus that point, in the face's frame
  };
  void weld(const Mesh& file, double tolerance);
  void split_non_manifold(const Vertices& V);
  void attach_unreferenced(const Mesh& file);
  Attachment attachment(int face, const Eigen::Vector3d& p) const;  // p following solver face `face`
  void set_identity(const Mesh& file);

  Mesh solver_;
  LayoutStats stats_;
  bool identity_ = true;
  std::vector<int> solver_of_file_;  // first copy, -1: unreferenced
  std::vector<int> extra_start_;     // split vertices: more copies of file vertex v in
  std::vector<int> extra_copies_;    //   extra_copies_[extra_start_[v] .. extra_start_[v + 1])
  std::vector<int> file_of_solver_;
  std::vector<int> solver_face_of_file_;
  std::vector<int> file_face_of_solver_;
  std::vector<int> collapsed_at_;  // per file face: the solver vertex of a collapsed face's corners, or -1
  std::vector<std::pair<int, Attachment>> attachments_;  // unreferenced file vertex -> where it follows
};

}  // namespace sd
