#include "test_support.h"

#include <fstream>
#include <sstream>

#include "core/mesh/mesh_io.h"

namespace sd::test {

std::string shared_data_path(const std::string& name) {
  std::string path = std::string(SD_SHARED_DATA_DIR) + "/" + name;
  std::ifstream probe(path, std::ios::binary);
  return probe.good() ? path : std::string();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream content;
  content << in.rdbuf();
  return content.str();
}

Mesh load_shared_mesh(const std::string& name) {
  std::string path = shared_data_path(name);
  return read_mesh(read_file(path), name);
}

bool is_snake_case(const std::string& name) {
  if (name.empty() || name.front() == '_' || name.back() == '_') return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || c == '_')) return false;
  return true;
}

}  // namespace sd::test
