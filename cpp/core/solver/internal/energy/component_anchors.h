// Anchors for the components no handle holds (docs/method.md section 5.3). The energy is blind to each connected
// component's rigid motions (the rotation-invariant Laplacian coordinates turn with it, and a component's volume
// does not change when it moves), so a component without a handle vertex is held by nothing but its coupling to
// the others through the subspace: in the spectral basis and the full space (and ARAP) nothing at all, and a solve
// either fails to factor its matrices or throws the component away. Three of its vertices, as far apart as its
// shape allows, become a handle group of their own, held at their rest positions: such a component stays put.
#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// Per connected component of (X0, F) that contains none of `handles`: three of its vertices (fewer where its
// vertices are all collinear or it has fewer), the first, the farthest from it, and the farthest from their line.
std::vector<std::vector<int>> component_anchors(const Vertices& X0, const Faces& F, const std::vector<int>& handles);

}  // namespace sd
