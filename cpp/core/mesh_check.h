// Validation of a mesh and of a mesh + cage pair, with one readable finding per problem. The solver
// requires: closed, edge- and vertex-manifold, consistently and outward oriented, finite coordinates,
// no degenerate or duplicate faces; for a pair, every mesh vertex strictly inside the cage.
#pragma once

#include <string>
#include <vector>

#include "core/mesh.h"

namespace sd {

enum class Severity { Error, Warning };

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
  double volume = 0.0;  // signed; positive when outward oriented
};

struct CheckReport {
  MeshSummary summary;
  std::vector<Finding> findings;
  bool ok() const;             // no finding of severity Error
  std::string text() const;    // all findings, one per line, errors first
};

// `role` ("mesh" or "cage") prefixes the messages.
CheckReport check_mesh(const Mesh& mesh, const std::string& role = "mesh");

// Checks both meshes, then that every mesh vertex is strictly inside the cage (generalized winding
// number ~ 1 and not on the cage surface). The returned summary is the mesh's.
CheckReport check_mesh_in_cage(const Mesh& mesh, const Mesh& cage);

// Generalized winding number of point p with respect to a closed triangle mesh (Jacobson et al. 2013):
// ~1 inside, ~0 outside.
double winding_number(const Mesh& mesh, const Eigen::RowVector3d& p);

// Throws sd::Error with report.text() when the report has errors.
void throw_if_invalid(const CheckReport& report);

}  // namespace sd
