// Validation of a mesh and of a mesh + cage pair, with one readable finding per problem. Two levels:
//   - check_mesh: a mesh exactly as the solver takes it. A cage must be closed, edge- and vertex-manifold,
//     consistently and outward oriented, with finite coordinates and no degenerate or duplicate faces; a mesh
//     the same, or open under CheckOptions::model_rules (its volume is then the capped one: part_volume.h).
//   - check_model: a model as the user gives it (the file's vertex layout): its MeshLayout's solver mesh
//     (welded, non-manifold vertices split, unreferenced vertices left out: mesh_layout.h) checked with
//     open allowed, every index named in file numbering, plus notes on what the layout did. This is what the
//     Deformer, the CLI's check and the app apply, so they accept and refuse the same models.
// For a pair, every mesh vertex strictly inside the cage.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/mesh.h"
#include "core/mesh/mesh_layout.h"

namespace sd {

// Errors refuse the mesh; warnings say what may surprise; notes say what was done for it (welding, capping).
enum class Severity { Error, Warning, Note };

struct Finding {
  Severity severity;
  std::string code;     // stable machine-readable id, e.g. "open", "non_manifold_edge", "outside_cage"
  std::string message;  // for people, names counts and the first few offending indices
};

struct MeshSummary {
  int vertices = 0;
  int faces = 0;
  int edges = 0;
  int components = 0;
  int genus = -1;  // from the Euler characteristic when closed, manifold and one component; else -1
  Eigen::RowVector3d bbox_min = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d bbox_max = Eigen::RowVector3d::Zero();
  double volume = 0.0;  // signed; positive when outward oriented (open, allowed: with its holes capped)
  int holes = 0;        // boundary loops (open meshes)
  // check_model: what the layout did (mesh_layout.h); vertices and faces above are then the file's.
  LayoutStats layout;
};

struct CheckOptions {
  // The rules of a model's mesh (check_model): open is a note (each hole capped for the volume), not an error,
  // and several components a note (each keeps its own volume), not a warning.
  bool model_rules = false;
  const IndexNames* names = nullptr;  // file indices for the messages (check_model)
};

struct CheckReport {
  MeshSummary summary;
  std::vector<Finding> findings;
  bool ok() const;           // no finding of severity Error
  std::string text() const;  // all findings, one per line, errors first, then warnings, then notes
};

// |coordinate| above this is the error coordinates_too_large: volumes are cubic and the solver squares them and
// their gradients, which overflows double precision not far above this.
constexpr double kMaxMeshCoordinate = 1e30;

// `role` ("mesh" or "cage") prefixes the messages ("cage: the mesh is open: ...").
// Finding codes. Errors: no_faces, non_finite (NaN/inf coordinates), index_out_of_range,
// degenerate_face (repeated index, or area < 1e-14 x bbox diagonal^2), duplicate_face (same vertex set,
// either orientation), open (boundary edges), non_manifold_edge (> 2 faces), non_manifold_vertex (the
// faces around it form several fans), inconsistent_orientation (both faces of an edge walk it the same
// way), inward (closed, consistently oriented, negative volume: flip every face), flat (closed but its
// |volume| is below 1e-12 x bbox diagonal^3), coordinates_too_large (|x| > 1e30: volumes would overflow).
// Warnings: huge_coordinates (|x| > 1e12: usually wrong units; the algorithms are scale-free, so not an
// error), unreferenced_vertices, components (more than one), component_inward (a component with negative
// volume inside a positive total: a cavity wall or a flipped part).
// Summary: edges are the distinct undirected edges; components count face-connected vertex sets (numbered, in
// component_inward, in the order of their first face, as component_parts numbers a model's parts: partition.h);
// holes count the connected pieces of the boundary edges; the bounding box covers the finite vertices;
// genus = (2 - (V - E + F)) / 2 over the referenced vertices. The topological facts are topology.h's.
// Under model_rules, `open` and `components` are notes and flat/inward/component_inward use the capped volume.
CheckReport check_mesh(const Mesh& mesh, const std::string& role = "mesh", const CheckOptions& options = {});

// Checks both meshes, then that every mesh vertex is strictly inside the cage (generalized winding
// number ~ 1, geometry/winding_number.h, and not on the cage surface). The returned summary is the mesh's.
// Extra error codes: outside_cage (winding number <= 1/2), on_cage (within 1e-9 x cage bbox diagonal of
// a cage face), self_intersecting (two cage faces cross; tested when the cage alone is valid). The inside
// test is skipped when the cage has no faces, bad indices or non-finite coordinates (those are already
// errors). Cost O(#mesh vertices x #cage faces): about 20 ns per pair
// natively (50k x 1280 in 1.3 s).
CheckReport check_mesh_in_cage(const Mesh& mesh, const Mesh& cage, const CheckOptions& mesh_options = {});

// The model level (see the top): the layout's solver mesh, open allowed, indices in file numbering. Notes:
// welded (vertices at one point merged for the solver), collapsed_faces (faces whose corners welded together),
// split_vertices (non-manifold vertices and edges split), open, components (each keeps its own volume);
// warning: unreferenced_vertices (carried along with the nearest triangle). The summary counts the file's
// vertices and faces, and the layout's statistics.
CheckReport check_model(const MeshLayout& layout);
CheckReport check_model(const Mesh& mesh, const LayoutOptions& options = {});
// check_model and the inside test on the solver mesh's vertices.
CheckReport check_model_in_cage(const MeshLayout& layout, const Mesh& cage);

// A mesh or cage that failed the checks: what() is the report's text, findings() every finding (warnings
// included), code() MeshOutsideCage when the only errors are outside_cage / on_cage, else InvalidMesh.
class MeshError : public Error {
 public:
  // `context` goes before the report's text (e.g. "cage generation needs a valid closed mesh:\n").
  explicit MeshError(const CheckReport& report, const std::string& context = "");
  const std::vector<Finding>& findings() const { return findings_; }

 private:
  std::vector<Finding> findings_;
};

// Throws MeshError when the report has errors.
void throw_if_invalid(const CheckReport& report);

}  // namespace sd
