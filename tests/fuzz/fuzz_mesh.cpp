// libFuzzer target for the mesh readers and checks (built and run by scripts/fuzz.sh).
// Every reader must either return a mesh or throw sd::Error; any other exception, crash, sanitizer
// report or a failed OBJ write/read round trip is a finding. Successful parses go through the checks.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstdio>
#include <string_view>

#include "core/error.h"
#include "core/mesh/mesh_check.h"
#include "core/mesh/mesh_io.h"
#include "core/mesh/mesh_layout.h"

namespace {

// write_obj then read_obj must give back the same mesh, to the bit. A mesh with a NaN or infinite coordinate (the
// readers parse them; the checks report them) must be refused by write_obj with sd::Error: "v nan 0 0" is no OBJ.
void check_round_trip(const sd::Mesh& mesh) {
  if (!mesh.V.allFinite()) {
    try {
      (void)sd::write_obj(mesh, "fuzz");
    } catch (const sd::Error&) {
      return;
    }
    std::abort();
  }
  const sd::Mesh back = sd::read_obj(sd::write_obj(mesh, "fuzz"));
  if (back.V.rows() != mesh.V.rows() || back.F != mesh.F) std::abort();
  for (Eigen::Index i = 0; i < mesh.V.size(); ++i)
    if (mesh.V.data()[i] != back.V.data()[i]) std::abort();
}

// The vertex layout of any parsed mesh: the model check runs, every solver face's indices are in range, and
// positions map back to the file's vertex count (the solver mesh itself at rest).
void check_layout(const sd::Mesh& mesh) {
  const sd::MeshLayout layout(mesh);
  (void)sd::check_model(layout).text();
  const sd::Mesh& solver = layout.mesh();
  if (solver.F.size() > 0 && (solver.F.minCoeff() < 0 || solver.F.maxCoeff() >= solver.V.rows())) std::abort();
  if (layout.to_file(solver.V).rows() != mesh.V.rows()) std::abort();
}

void exercise(sd::Mesh (*reader)(std::string_view), std::string_view bytes) {
  sd::Mesh mesh;
  try {
    mesh = reader(bytes);
  } catch (const sd::Error&) {
    return;  // a readable rejection is the expected outcome for most inputs
  }
  if (mesh.F.rows() == 0) std::abort();  // readers promise at least one face
  const sd::CheckReport report = sd::check_mesh(mesh);
  (void)report.text();
  check_round_trip(mesh);
  check_layout(mesh);
  // The pair check is O(V F): keep it to small meshes so the fuzzer stays fast. The mesh is its own
  // cage here, so every vertex is on the cage surface.
  if (mesh.V.rows() * mesh.F.rows() <= 20000) (void)sd::check_mesh_in_cage(mesh, mesh);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  exercise(sd::read_obj, bytes);
  exercise(sd::read_off, bytes);
  exercise(sd::read_ply, bytes);
  exercise(sd::read_stl, bytes);
  try {
    (void)sd::read_mesh(bytes, "fuzz-input");  // format sniffing path
  } catch (const sd::Error&) {
  }
  return 0;
}
