// Helpers shared by the native tests: access to the real meshes in ../shared/data (tests skip, saying
// why, when that folder is absent) and small numeric helpers. Procedural meshes: core/mesh/shapes.h.
#pragma once

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "core/error.h"
#include "core/mesh/mesh.h"

namespace sd::test {

// Full path of ../shared/data/<name>, or "" when that file is absent.
std::string shared_data_path(const std::string& name);
std::string read_file(const std::string& path);
// Parses ../shared/data/<name> (call SD_REQUIRE_SHARED_DATA(name) first).
Mesh load_shared_mesh(const std::string& name);
// Lower-case letters and inner underscores only: the spelling of the codes JS sees.
bool is_snake_case(const std::string& name);

// `mesh` without the triangles whose centroid satisfies `drop` (holes), and without the vertices no triangle
// uses any more (renumbered in order): an open mesh for the tests of open meshes.
Mesh drop_faces(const Mesh& mesh, const std::function<bool(const Eigen::RowVector3d& centroid)>& drop);
// Two meshes as one (the second's indices shifted): separate components.
Mesh join_meshes(const Mesh& a, const Mesh& b);
// `mesh` moved by `by` (its triangles kept): a model far from the origin, for the tests of its volume's digits.
Mesh translated(const Mesh& mesh, const Eigen::RowVector3d& by);

// Fails the current test unless `call` throws sd::Error whose message contains `fragment` (and, when given,
// whose code is `code`).
void expect_error(const std::function<void()>& call, const std::string& fragment);
void expect_error(const std::function<void()>& call, const std::string& fragment, ErrorCode code);

// Central differences of f at U (m by 3 unknowns) with step h: column a * m + j is d f / d U(j, a).
Eigen::MatrixXd central_differences(const Eigen::MatrixXd& U,
                                    const std::function<Eigen::VectorXd(const Eigen::MatrixXd&)>& f, double h = 1e-6);
// The largest |central difference - g(j, a)| for the gradient g (m by 3) of the scalar f at U.
double gradient_error(const Eigen::MatrixXd& U, const Eigen::MatrixXd& g,
                      const std::function<double(const Eigen::MatrixXd&)>& f, double h = 1e-6);

}  // namespace sd::test

// Skips the current test, saying why, when ../shared/data/<name> is absent.
#define SD_REQUIRE_SHARED_DATA(name)                                                          \
  do {                                                                                        \
    if (sd::test::shared_data_path(name).empty())                                             \
      GTEST_SKIP() << "../shared/data/" << (name)                                             \
                   << " is absent (test data lives beside the project, not in it); skipping"; \
  } while (0)
