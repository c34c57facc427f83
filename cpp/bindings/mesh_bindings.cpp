// Mesh reading, writing, validation and the built-in examples, for JS.
// Wrapped by web/lib/mesh.js, which validates arguments before they get here.
#include <emscripten/bind.h>

#include "bindings/convert.h"
#include "core/mesh/examples.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_io.h"

namespace sd::bindings {
namespace {

val read_mesh_js(const val& bytes, const std::string& filename) {
  return guarded([&] { return mesh_to_js(read_mesh(bytes_from_js(bytes), filename)); });
}

std::string write_obj_js(const val& positions, const val& indices, const std::string& comment) {
  return guarded([&] { return write_obj(mesh_from_js(positions, indices, "mesh"), comment); });
}

val vector3_to_js(const Eigen::RowVector3d& v) {
  val out = val::array();
  for (int k = 0; k < 3; ++k) out.call<void>("push", v[k]);
  return out;
}

val report_to_js(const CheckReport& report) {
  val summary = val::object();
  summary.set("vertices", report.summary.vertices);
  summary.set("faces", report.summary.faces);
  summary.set("edges", report.summary.edges);
  summary.set("components", report.summary.components);
  summary.set("genus", report.summary.genus);
  summary.set("bboxMin", vector3_to_js(report.summary.bbox_min));
  summary.set("bboxMax", vector3_to_js(report.summary.bbox_max));
  summary.set("volume", report.summary.volume);
  summary.set("holes", report.summary.holes);
  summary.set("layout", layout_stats_to_js(report.summary.layout));
  val out = val::object();
  out.set("ok", report.ok());
  out.set("summary", summary);
  out.set("findings", findings_to_js(report.findings));
  out.set("text", report.text());
  return out;
}

// The model-level check (mesh_check.h): welded, open allowed, indices in the file's numbering.
val check_model_js(const val& positions, const val& indices, const val& options) {
  return guarded([&] {
    return report_to_js(check_model(mesh_from_js(positions, indices, "mesh"), layout_options_from_js(options)));
  });
}

val check_model_pair_js(const val& mesh_positions, const val& mesh_indices, const val& cage_positions,
                        const val& cage_indices, const val& options) {
  return guarded([&] {
    const MeshLayout layout(mesh_from_js(mesh_positions, mesh_indices, "mesh"), layout_options_from_js(options));
    return report_to_js(check_model_in_cage(layout, mesh_from_js(cage_positions, cage_indices, "cage")));
  });
}

val check_mesh_js(const val& positions, const val& indices, const std::string& role) {
  return guarded([&] { return report_to_js(check_mesh(mesh_from_js(positions, indices, role.c_str()), role)); });
}

val check_pair_js(const val& mesh_positions, const val& mesh_indices, const val& cage_positions,
                  const val& cage_indices) {
  return guarded([&] {
    return report_to_js(check_mesh_in_cage(mesh_from_js(mesh_positions, mesh_indices, "mesh"),
                                           mesh_from_js(cage_positions, cage_indices, "cage")));
  });
}

val example_names_js() {
  val out = val::array();
  for (const auto& name : example_names()) out.call<void>("push", name);
  return out;
}

val make_example_js(const std::string& name) {
  return guarded([&] {
    Example example = make_example(name);
    val out = val::object();
    out.set("name", example.name);
    out.set("description", example.description);
    out.set("mesh", mesh_to_js(example.mesh));
    out.set("cage", mesh_to_js(example.cage));
    return out;
  });
}

}  // namespace
}  // namespace sd::bindings

EMSCRIPTEN_BINDINGS(mesh) {
  using namespace sd::bindings;
  emscripten::function("readMesh", &read_mesh_js);
  emscripten::function("writeObj", &write_obj_js);
  emscripten::function("checkMesh", &check_mesh_js);
  emscripten::function("checkPair", &check_pair_js);
  emscripten::function("checkModel", &check_model_js);
  emscripten::function("checkModelPair", &check_model_pair_js);
  emscripten::function("exampleNames", &example_names_js);
  emscripten::function("makeExample", &make_example_js);
}
