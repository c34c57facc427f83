// Volume parts made automatically: spectral clustering of the surface into K parts.
//   1. Embedding. Each vertex i goes to y_i = (phi_1(i) / sqrt(lambda_1), .., phi_d(i) / sqrt(lambda_d)), the d
//      lowest non-trivial eigenpairs of -L phi = lambda M phi (laplacian_eigenpairs.h), d = K + 2: the Global
//      Point Signature (Rustamov 2007), truncated. Low modes vary slowly along the surface and tell protrusions
//      (limbs, head) apart; the 1 / sqrt(lambda) weights make the lowest count most.
//   2. k-means in that space, weighted by the vertices' areas (lumped mass): k-means++ seeding from a fixed seed
//      (so the parts are the same on every machine), Lloyd iterations until no vertex changes cluster, 8
//      restarts, the one with the least weighted squared distance kept.
//   3. Triangles go to the cluster holding at least two of their vertices (partition.h), then each part is made
//      connected: every face-connected piece but its largest joins the neighbouring part it shares most edges
//      with. Parts left empty are dropped and the rest renumbered 0 .. K'-1 (K' <= K; normally K' = K).
#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// One part index per triangle. Throws sd::Error when K < 1 or the mesh has too few vertices for K + 3
// eigenpairs, or as laplacian_eigenpairs does.
std::vector<int> auto_parts(const Mesh& mesh, int parts);

}  // namespace sd
