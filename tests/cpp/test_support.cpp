#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <vector>

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

Mesh drop_faces(const Mesh& mesh, const std::function<bool(const Eigen::RowVector3d& centroid)>& drop) {
  std::vector<int> kept;
  for (int f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::RowVector3d c = (mesh.V.row(mesh.F(f, 0)) + mesh.V.row(mesh.F(f, 1)) + mesh.V.row(mesh.F(f, 2))) / 3.0;
    if (!drop(c)) kept.push_back(f);
  }
  std::vector<int> index(static_cast<size_t>(mesh.V.rows()), -1);
  for (int f : kept)
    for (int k = 0; k < 3; ++k) index[mesh.F(f, k)] = 0;
  int next = 0;
  for (int& i : index)
    if (i == 0) i = next++;
  Mesh out;
  out.V.resize(next, 3);
  for (int v = 0; v < mesh.V.rows(); ++v)
    if (index[v] >= 0) out.V.row(index[v]) = mesh.V.row(v);
  out.F.resize(static_cast<int>(kept.size()), 3);
  for (size_t r = 0; r < kept.size(); ++r)
    for (int k = 0; k < 3; ++k) out.F(static_cast<int>(r), k) = index[mesh.F(kept[r], k)];
  return out;
}

Mesh join_meshes(const Mesh& a, const Mesh& b) {
  Mesh m;
  m.V.resize(a.V.rows() + b.V.rows(), 3);
  m.V << a.V, b.V;
  m.F.resize(a.F.rows() + b.F.rows(), 3);
  m.F << a.F, (b.F.array() + static_cast<int>(a.V.rows())).matrix();
  return m;
}

Mesh translated(const Mesh& mesh, const Eigen::RowVector3d& by) {
  Mesh m = mesh;
  m.V.rowwise() += by;
  return m;
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

Eigen::MatrixXd central_differences(const Eigen::MatrixXd& U,
                                    const std::function<Eigen::VectorXd(const Eigen::MatrixXd&)>& f, double h) {
  const Eigen::Index m = U.rows();
  Eigen::MatrixXd J;
  for (int a = 0; a < 3; ++a)
    for (Eigen::Index j = 0; j < m; ++j) {
      Eigen::MatrixXd Up = U, Um = U;
      Up(j, a) += h;
      Um(j, a) -= h;
      const Eigen::VectorXd column = (f(Up) - f(Um)) / (2 * h);
      if (J.size() == 0) J.resize(column.size(), 3 * m);
      J.col(a * m + j) = column;
    }
  return J;
}

double gradient_error(const Eigen::MatrixXd& U, const Eigen::MatrixXd& g,
                      const std::function<double(const Eigen::MatrixXd&)>& f, double h) {
  const Eigen::MatrixXd fd = central_differences(
      U, [&](const Eigen::MatrixXd& V) { return Eigen::VectorXd::Constant(1, f(V)); }, h);
  double worst = 0;
  for (int a = 0; a < 3; ++a)
    for (Eigen::Index j = 0; j < U.rows(); ++j) worst = std::max(worst, std::abs(fd(0, a * U.rows() + j) - g(j, a)));
  return worst;
}

}  // namespace sd::test
