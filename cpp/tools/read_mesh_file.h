// A mesh file read whole and parsed by its extension (core/mesh/mesh_io.h), for the native tools.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/mesh/mesh_io.h"

namespace sd::tools {

inline Mesh read_mesh_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + path);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return read_mesh(bytes.str(), path);
}

}  // namespace sd::tools
