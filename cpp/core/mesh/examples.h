// Built-in example models: procedural meshes with cages made here, so the app and the tests need no
// third-party files. Each mesh is closed, manifold, outward and strictly inside its cage.
#pragma once

#include <string>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd {

struct Example {
  std::string name;
  std::string description;
  Mesh mesh;
  Mesh cage;
};

// Names accepted by make_example, the default first.
std::vector<std::string> example_names();

// Throws sd::Error listing the valid names when `name` is unknown.
Example make_example(const std::string& name);

}  // namespace sd
