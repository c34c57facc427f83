// How the deformation energy weights its terms (docs/method.md section 5.1).
//
// EnergyWeighting::Uniform is the original report's energy: every vertex's Laplacian residual and every handle
// vertex count once. A row of the cotangent Laplacian scales like the vertex's area, so the Laplacian term shrinks
// like h^2 under refinement while the handle term grows like 1/h^2 (one term per handle vertex): the same scene
// gives a different shape at every resolution.
//
// EnergyWeighting::Area makes both terms integrals over the surface, so the answer converges under refinement.
// With A_i the lumped (barycentric) area of vertex i, A the surface's area and A_ref = A / kReferenceVertexCount
// (the area of one vertex if the surface were sampled by that many evenly spread vertices):
//   Laplacian:  sum_i (A_ref / A_i) |(L X)_i - delta_hat_i(X)|^2     ~  A_ref * integral of |Delta x - delta|^2
//   handles:    sum_g (max(A_g, A_ref) / A_ref) sum_{k in g} (a_k / A_g) |x_k - v_k|^2
// for handle groups g of area A_g = sum_{k in g} a_k. A group pulls with the weight of the reference vertices it
// covers (at least one, so a single picked vertex keeps its pull however fine the mesh), spread over its vertices
// by area. At kReferenceVertexCount evenly spread vertices both sums equal the uniform ones, so the default
// position weight means what it meant for meshes of that size; and both scale like length^2 with the model, as
// the uniform energy does.
//
// The solver applies the weights as row scales: the Laplacian rows are multiplied by s_i = sqrt(A_ref / A_i)
// (L becomes S L, and the rotation-invariant coordinates fitted to S L X0 keep the rest pose exact), and handle
// row k by sqrt(c_k) with c_k its coefficient above.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/solver/solver_types.h"

namespace sd {

// The vertex count at which the area-weighted energy equals the uniform one (see above).
constexpr double kReferenceVertexCount = 5000.0;

class EnergyWeights {
 public:
  // Lumped areas of the rest mesh. Throws sd::Error (InvalidMesh) when a vertex has no area around it.
  EnergyWeights(const Vertices& X0, const Faces& F);

  // s_i per vertex: sqrt(A_ref / A_i) with Area, 1 with Uniform.
  Eigen::VectorXd laplacian_row_scales(EnergyWeighting weighting) const;
  // c_k per handle vertex (vertices in group order; group_sizes sum to vertices.size()): 1 with Uniform.
  Eigen::VectorXd handle_coefficients(EnergyWeighting weighting, const std::vector<int>& vertices,
                                      const std::vector<int>& group_sizes) const;

  const Eigen::VectorXd& vertex_areas() const { return areas_; }
  double reference_area() const { return reference_area_; }

 private:
  Eigen::VectorXd areas_;
  double reference_area_ = 0;
};

}  // namespace sd
