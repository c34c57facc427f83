#include "core/mesh/examples.h"

#include "core/error.h"
#include "core/mesh/shapes.h"

namespace sd {
namespace {

// A capsule of length 4 and radius 0.5 along x inside a box cage with `cage_segments` slabs along x, so
// the cage (and with it the bar) can bend. The cage keeps a 0.2 clearance around the capsule.
Example bar(const std::string& name, int rings, int cylinder_rings, int segments, int cage_segments) {
  Example e;
  e.name = name;
  e.mesh = make_capsule(4.0, 0.5, rings, cylinder_rings, segments);
  e.cage = make_bar_cage(-2.7, 2.7, 0.7, 0.7, cage_segments);
  e.description = "capsule bar, " + std::to_string(e.mesh.V.rows()) + " vertices, box cage of " +
                  std::to_string(e.cage.V.rows()) + " vertices";
  return e;
}

// The bar bent through 3/4 of a turn into a C opening towards +x, in its own bent cage: the cage is concave
// inside the C, where its two arms face each other, so mean value weights go negative there (the example for
// comparing cage coordinates). The cage's 12 slabs keep its flat faces clear of the bent capsule.
Example c_bar() {
  Example e = bar("c-bar", 12, 40, 80, 12);
  const double radius = 5.4 / (1.5 * 3.14159265358979323846);
  for (Mesh* m : {&e.mesh, &e.cage}) {
    const Vertices bent = bend_along_x(m->V, radius);
    // A quarter turn about the bend's centre (0, radius): the opening, at +y, turns to +x.
    for (Eigen::Index i = 0; i < bent.rows(); ++i) m->V.row(i) << bent(i, 1) - radius, -bent(i, 0), bent(i, 2);
  }
  e.description = "capsule bent into a C, " + std::to_string(e.mesh.V.rows()) + " vertices, in its bent cage of " +
                  std::to_string(e.cage.V.rows()) + " vertices (concave inside the C)";
  return e;
}

// A fine sphere inside a coarse icosphere. The coarse faces' inradius is about 0.95 of its radius, so a
// cage radius of 1.3 leaves clearance around the unit sphere.
Example sphere() {
  Example e;
  e.name = "sphere";
  e.mesh = make_icosphere(5, 1.0);
  e.cage = make_icosphere(1, 1.3);
  e.description = "sphere, " + std::to_string(e.mesh.V.rows()) + " vertices, icosphere cage of " +
                  std::to_string(e.cage.V.rows()) + " vertices";
  return e;
}

}  // namespace

std::vector<std::string> example_names() { return {"bar", "sphere", "bar-fine", "c-bar"}; }

Example make_example(const std::string& name) {
  if (name == "bar") return bar(name, 12, 40, 80, 6);          // ~5k vertices, 28-vertex cage
  if (name == "bar-fine") return bar(name, 30, 120, 240, 12);  // ~43k vertices, 52-vertex cage
  if (name == "sphere") return sphere();                       // ~10k vertices, 42-vertex cage
  if (name == "c-bar") return c_bar();                         // ~5k vertices, 52-vertex cage
  std::string known;
  for (const auto& n : example_names()) known += (known.empty() ? "" : ", ") + n;
  throw Error("unknown example '" + name + "' (built-in examples: " + known + ")");
}

}  // namespace sd
