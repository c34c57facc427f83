// Volumes of the parts of a mesh: K parts, a partition of its triangles (part_of_face), each part's volume the
// signed volume enclosed by its triangles closed by caps over its boundary. The mesh may be open: its own
// boundary (edges with a single triangle) is capped the same way, so an open mesh's volume is the volume it
// encloses once every hole is closed by the fan from the hole's centroid (docs/method.md section 5).
//
// Caps. The boundary between two parts p < q is a set of interface curves: maximal paths of edges shared by p
// and q whose inner vertices are on no other interface ("junctions", where three or more parts meet or a curve
// branches, end them), or closed loops without a junction. Each curve is capped by the fan from its centroid c
// (the mean of its vertices): triangles (b, a, c) over its edges a -> b as p's triangles run them. An open curve
// (from junction s to junction e) is closed by its chord: the triangle (c, s, e); the chords of a part's open
// curves form closed polygons through the junctions, capped by the fan from one common point o, the mean of all
// junctions: triangles (e, s, o). Part q uses every cap triangle reversed.
//   - With two parts meeting along loops (a neck cut) this is just "each boundary loop closed by the fan from
//     its centroid".
//   - The mesh's own boundary works as an interface with an outside part that has no volume: a hole of one part
//     is a closed loop capped by its fan; where a hole's rim crosses from part p to part q its pieces are open
//     curves between junctions like any other. Those caps appear once, so for an open mesh the part volumes add
//     up to the capped volume of the whole.
//   - Every part's surface (its triangles and caps) is closed, so each part volume is translation (and
//     rotation) invariant; and every cap triangle appears twice with opposite orientations, so the part volumes
//     add up to the volume of the whole mesh, whatever the partition (three parts may meet at points).
//   - Each volume is a cubic polynomial in the vertex positions (centroids are linear in them): differentiable
//     everywhere; gradients() gives it exactly (tested against finite differences).
// With one part of a closed mesh there are no caps, and the arithmetic is that of signed_volume and
// volume_gradient (core/mesh/volume.h), to the bit: the triangle sums go through signed_volumes, blocked as
// signed_volume.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/mesh/volume.h"

namespace sd {

class PartVolumes {
 public:
  // part_of_face: one part index per triangle, in [0, K), every part used (validate with validate_parts,
  // partition.h). The mesh must be edge-manifold and consistently oriented, open or closed (checked by the
  // caller, as for the solver); an edge with more than two triangles is an sd::Error.
  PartVolumes(const Faces& F, int vertex_count, const std::vector<int>& part_of_face);

  int count() const { return count_; }
  const std::vector<int>& part_of_face() const { return part_; }
  int curve_count() const { return static_cast<int>(curves_.size()); }
  // Curves on the mesh's own boundary (0 for a closed mesh): with one part, the holes.
  int boundary_curve_count() const;
  int junction_count() const { return static_cast<int>(junctions_.size()); }

  // The K part volumes at X, every term summed about the reference point r (volume.h: near the model, so that a
  // model far from the origin keeps its digits; a solver fixes it at bind, a standalone measure takes
  // volume_reference(X, F)).
  Eigen::VectorXd evaluate(const Vertices& X, const VolumeReference& r) const;
  // With one part: the mesh (X, F) closed by its caps, a new vertex at each hole's centroid and the fan from it
  // (what evaluate() measures, as a mesh: for cage generation around an open mesh). Throws sd::Error with more
  // than one part.
  Mesh closed_mesh(const Vertices& X) const;
  // Their gradients: #V by 3K, columns 3k .. 3k + 2 the gradient of part k's volume (the solver's block layout).
  // About r as evaluate().
  Eigen::MatrixXd gradients(const Vertices& X, const VolumeReference& r) const;

 private:
  struct Curve {
    int p = 0, q = 0;                        // p < q; the half-edges run as in p's triangles; q = K: the
                                             // mesh's boundary (no part on the other side)
    std::vector<std::pair<int, int>> edges;  // a -> b
    std::vector<int> vertices;               // for the centroid (each once)
    bool closed = true;
    int start = -1, end = -1;  // open curves: first and last vertex along p's direction
  };
  void find_curves(int vertex_count);
  // The mean of the junctions, relative to r.
  Eigen::RowVector3d junction_centre(const Vertices& X, const VolumeReference& r) const;

  Faces F_;
  VertexTriangles around_;  // the triangles around each vertex, for the gathered gradients
  std::vector<int> part_;
  int count_ = 0;
  std::vector<Curve> curves_;
  std::vector<int> junctions_;
};

// The volume parts a mesh gets unless told otherwise: one per connected component (component_parts,
// partition.h), so that separate bodies each keep their own volume instead of trading it; a component that
// encloses no volume (|V| <= 1e-12 x its own bounding-box diagonal cubed: a flat sheet) has none to keep and joins
// the part of the component with the largest |volume|. Empty when the mesh is one closed component: its one
// global volume needs no parts (and keeps signed_volume's arithmetic); one part (all zeros) for a single open
// component, whose holes need capping. With more than 32 components the 31 with the largest |volume| keep
// their own parts and the others share one (each part is a constraint of every iteration).
std::vector<int> default_volume_parts(const Vertices& X0, const Faces& F);

// The volume of the mesh as the solver keeps it: the sum of its default parts' volumes (with every hole capped),
// psi for one closed component; about the mesh's own volume_reference.
double enclosed_volume(const Vertices& X, const Faces& F);

}  // namespace sd
