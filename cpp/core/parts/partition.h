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
// and a restoration direction per iteration (method.md section 16), so a partition with one part per triangle
// (10k parts) took a minute and gigabytes before failing; a thousand parts is already far finer than volumes
// worth keeping. Checked before any work: on the lists' count, the highest part index, and K of auto_parts.
constexpr int kMaxVolumeParts = 1000;

// The number of parts K of a partition: part_of_face must have one entry per triangle, in [0, K), and every
// part in [0, K) must have a triangle, and K <= kMaxVolumeParts. Throws sd::Error naming the first problem.
int validate_parts(const std::vector<int>& part_of_face, int face_count);

// Both refuse more than kMaxVolumeParts lists at once, and a result with more than kMaxVolumeParts parts (the
// lists and the unlisted rest).
std::vector<int> parts_from_triangle_lists(const std::vector<std::vector<int>>& lists, int face_count);
std::vector<int> parts_from_vertex_lists(const std::vector<std::vector<int>>& lists, const Faces& F, int vertex_count);
// The same rule from one part index per vertex (every vertex assigned).
std::vector<int> parts_from_vertex_labels(const std::vector<int>& vertex_part, const Faces& F);

// Makes every part face-connected (across edges): each piece but the largest of its part joins the neighbouring
// part it shares most edges with.
void connect_parts(std::vector<int>& part, const Faces& F);
// Renumbers the parts in use to 0 .. K'-1, keeping their order (drops indices no triangle has).
void compact_parts(std::vector<int>& part);

}  // namespace sd
