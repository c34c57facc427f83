// Volume parts as data: a partition of a mesh's triangles into K parts (one part index per triangle), made
// from the lists a scene or the app gives, checked, made connected and renumbered.
//
// From triangle lists: list j is part j; triangles in no list form one more part, the rest (the last index).
// From vertex lists: list j is part j; vertices in no list belong to the rest (the last index, when there are
// any); a triangle goes to the part that holds at least two of its vertices, or, when its three vertices are in
// three different parts, to the lowest of them; every vertex list must so get a triangle. Either way no index
// may appear in two lists, and a list may not be empty (sd::Error naming the list and the index).
#pragma once

#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

// The most parts a partition may have, explicit or automatic. Each part adds a hard constraint, a multiplier
// and a restoration direction per iteration (method.md section 16): in the full space every part costs a
// preconditioner solve per iteration (the 5k-vertex bar: 0.1 s per iteration with one part, 2-3 s with 64, about
// 35 s with 1000), and automatic parts cost K + 3 eigenpairs and a k-means whose work grows like K^2 (1000 on a
// 10k-vertex sphere ran over 5 minutes); one part per triangle (10k parts) took a minute and gigabytes before
// failing. 64 is four times what the app paints or makes automatically (16) and twice the default components'
// cap (32). Checked before any work: on the lists' count, the highest part index, and K of auto_parts.
constexpr int kMaxVolumeParts = 64;

// The number of parts K of a partition: part_of_face must have one entry per triangle, in [0, K), and every
// part in [0, K) must have a triangle, and K <= kMaxVolumeParts. Throws sd::Error naming the first problem.
int validate_parts(const std::vector<int>& part_of_face, int face_count);

// Both refuse more than kMaxVolumeParts lists at once, and a result with more than kMaxVolumeParts parts (the
// lists and the unlisted rest).
std::vector<int> parts_from_triangle_lists(const std::vector<std::vector<int>>& lists, int face_count);
std::vector<int> parts_from_vertex_lists(const std::vector<std::vector<int>>& lists, const Faces& F, int vertex_count);
// The same rule from one part index per vertex (every vertex assigned).
std::vector<int> parts_from_vertex_labels(const std::vector<int>& vertex_part, const Faces& F);

// The connected components of a mesh (triangles joined through shared vertices, which for the edge- and
// vertex-manifold meshes the solver takes is through shared edges): one index per triangle, numbered in the
// order of their first triangle.
std::vector<int> component_parts(const Faces& F);

// Makes every part face-connected (across edges): each piece but the largest of its part joins the neighbouring
// part it shares most edges with.
void connect_parts(std::vector<int>& part, const Faces& F);
// Renumbers the parts in use to 0 .. K'-1, keeping their order (drops indices no triangle has).
void compact_parts(std::vector<int>& part);

}  // namespace sd
