#include "test_support.h"

#include <fstream>
#include <sstream>

#include "core/error.h"
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

namespace {

void expect_error_with(const std::function<void()>& call, const std::string& fragment, const ErrorCode* code) {
  try {
    call();
    ADD_FAILURE() << "expected sd::Error containing '" << fragment << "'";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    if (code) EXPECT_EQ(error_code_name(e.code()), std::string(error_code_name(*code))) << e.what();
  }
}

}  // namespace

void expect_error(const std::function<void()>& call, const std::string& fragment) {
  expect_error_with(call, fragment, nullptr);
}

void expect_error(const std::function<void()>& call, const std::string& fragment, ErrorCode code) {
  expect_error_with(call, fragment, &code);
}

bool is_snake_case(const std::string& name) {
  if (name.empty() || name.front() == '_' || name.back() == '_') return false;
  for (char c : name)
    if (!((c >= 'a' && c <= 'z') || c == '_')) return false;
  return true;
}

}  // namespace sd::test
