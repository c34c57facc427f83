// Procedural closed, manifold, outward-oriented meshes: the built-in examples and the test fixtures.
// The project ships no third-party model files, so everything the app shows by default is made here.
#pragma once

#include "core/mesh/mesh.h"

namespace sd {

// Axis-aligned box centred at the origin with side lengths (sx, sy, sz); each face is split into
// `subdivisions` x `subdivisions` quads (two triangles each).
Mesh make_box(double sx, double sy, double sz, int subdivisions = 1);

// Box cage around a bar-like model: a box with `segments` subdivisions along x and 1 across, so the
// cage can bend. Spans [x0, x1] x [-hy, hy] x [-hz, hz].
Mesh make_bar_cage(double x0, double x1, double hy, double hz, int segments);

// Icosahedron subdivided `subdivisions` times, projected on the sphere of `radius` at the origin.
Mesh make_icosphere(int subdivisions, double radius = 1.0);

// Capsule along x: a cylinder of `length` (x from -length/2 to length/2) capped by hemispheres of
// `radius`. `rings` latitude rings per hemisphere, `cylinder_rings` rings along the cylinder, `segments`
// vertices around.
Mesh make_capsule(double length, double radius, int rings, int cylinder_rings, int segments);

// Torus about the z axis (genus 1): tube of `minor_radius` around the circle of `major_radius`, `rings` vertices
// around the z axis by `segments` around the tube.
Mesh make_torus(double major_radius, double minor_radius, int rings, int segments);

// Bends a shape lying along x into an arc in the xy plane: the line y = 0 becomes the circle of `radius` about
// (0, radius, 0), its point x going to the angle x / radius; a point at height y lies at radius - y from the
// centre (so +y is the inside of the bend), z is kept. Lengths along y = 0 are kept, so a bar of length L
// bends through L / radius radians (3 pi / 2: a C). The map is smooth and one-to-one for |y| < radius and
// |x| / radius < pi, so a mesh inside a cage stays inside the bent cage when the cage's flat faces stay clear
// of the bent mesh (enough segments along x).
Vertices bend_along_x(const Vertices& V, double radius);

}  // namespace sd
