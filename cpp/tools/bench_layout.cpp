// Native benchmark of the vertex layout (core/mesh/mesh_layout.h) and the model check, on meshes as files
// give them and as exporters split them. Usage:
//   bench_layout [mesh files...]
// Without files it uses a procedural 25k-vertex capsule. For each mesh, three layouts: the file as it is
// (indexed), every face with its own three corners (what non-indexed and flat-shaded exports write: the
// welding's worst case), and the same with about a tenth of the faces dropped in patches (holes to cap,
// components, bowtie vertices to split). Each
// line gives the counts (file and solver vertices, welded, holes, components) and the median time of 5 runs
// of the layout alone, of check_model (layout + every check) and of the default volume parts (components).
#include <algorithm>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/mesh_layout.h"
#include "core/mesh/shapes.h"
#include "core/parts/partition.h"
#include "core/timer.h"
#include "tools/read_mesh_file.h"

namespace {

// Every face with its own three vertices, in face order.
sd::Mesh per_corner(const sd::Mesh& m) {
  sd::Mesh out;
  out.V.resize(3 * m.F.rows(), 3);
  out.F.resize(m.F.rows(), 3);
  for (int f = 0; f < m.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      out.V.row(3 * f + k) = m.V.row(m.F(f, k));
      out.F(f, k) = 3 * f + k;
    }
  return out;
}

// The mesh without the faces whose first vertex falls in every 8th cell of a coarse grid (holes in patches).
sd::Mesh with_holes(const sd::Mesh& m) {
  const Eigen::RowVector3d lo = m.V.colwise().minCoeff();
  const double cell = sd::bounding_box_diagonal(m.V) / 12;
  std::vector<int> kept;
  for (int f = 0; f < m.F.rows(); ++f) {
    const Eigen::RowVector3d c = (m.V.row(m.F(f, 0)) - lo) / cell;
    const int key = static_cast<int>(c.x()) + 2 * static_cast<int>(c.y()) + 4 * static_cast<int>(c.z());
    if (key % 8 != 3) kept.push_back(f);
  }
  sd::Mesh out;
  out.V = m.V;
  out.F.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (size_t i = 0; i < kept.size(); ++i) out.F.row(static_cast<Eigen::Index>(i)) = m.F.row(kept[i]);
  return out;
}

// Median milliseconds of 5 runs of `run`.
double median_ms(const std::function<void()>& run) {
  std::vector<double> ms;
  for (int k = 0; k < 5; ++k) {
    const sd::Timer timer;
    run();
    ms.push_back(timer.ms());
  }
  std::sort(ms.begin(), ms.end());
  return ms[2];
}

void bench(const std::string& name, const sd::Mesh& file) {
  const sd::MeshLayout layout(file);
  const sd::LayoutStats& s = layout.stats();
  const sd::CheckReport report = sd::check_model(layout);
  const double layout_ms = median_ms([&] { const sd::MeshLayout again(file); });
  const double check_ms = median_ms([&] { const sd::CheckReport again = sd::check_model(file); });
  int components = 0;
  const double parts_ms = median_ms([&] {
    const std::vector<int> parts = sd::component_parts(layout.mesh().F);
    components = parts.empty() ? 0 : *std::max_element(parts.begin(), parts.end()) + 1;
  });
  std::printf(
      "%-34s file %8d v %8d f | solver %8d v, welded %8d, unreferenced %d, split %d, holes %4d, components %d, %s"
      " | layout %7.1f ms, check_model %7.1f ms, components %6.1f ms\n",
      name.c_str(), s.file_vertices, s.file_faces, s.solver_vertices, s.welded, s.unreferenced, s.split_vertices,
      report.summary.holes, components, report.ok() ? "valid" : "INVALID", layout_ms, check_ms, parts_ms);
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::vector<std::pair<std::string, sd::Mesh>> meshes;
    for (int i = 1; i < argc; ++i) meshes.emplace_back(argv[i], sd::tools::read_mesh_file(argv[i]));
    if (meshes.empty()) meshes.emplace_back("capsule", sd::make_capsule(3.0, 0.6, 30, 60, 208));
    for (const auto& [path, mesh] : meshes) {
      const std::string name = path.substr(path.find_last_of('/') + 1);
      bench(name, mesh);
      bench(name + " per corner", per_corner(mesh));
      bench(name + " per corner, holes", per_corner(with_holes(mesh)));
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_layout: %s\n", e.what());
    return 1;
  }
}
