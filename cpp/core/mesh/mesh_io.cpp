// Format detection, dispatch to the per-format readers (internal/*_reader.cpp) and the OBJ writer.
#include "core/mesh/mesh_io.h"

#include <cstdint>
#include <cstdio>
#include <string>

#include "core/error.h"
#include "core/mesh/internal/mesh_parsing.h"

namespace sd {

using namespace parsing;

std::string write_obj(const Mesh& mesh, std::string_view comment) {
  std::string out;
  out.reserve(static_cast<size_t>(mesh.V.rows()) * 60 + static_cast<size_t>(mesh.F.rows()) * 24);
  size_t start = 0;
  while (start < comment.size()) {
    size_t end = comment.find('\n', start);
    if (end == std::string_view::npos) end = comment.size();
    out += "# ";
    out += comment.substr(start, end - start);
    out += '\n';
    start = end + 1;
  }
  char line[128];
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) {
    // "v nan 0 0" is no OBJ any reader takes back (this one refuses it): refuse to write one.
    if (!mesh.V.row(i).allFinite())
      throw Error("write_obj: vertex " + std::to_string(i) +
                  " has a NaN or infinite coordinate; an OBJ file cannot hold it");
    // %.17g: 17 significant digits always round-trip a double exactly.
    int n = std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
    out.append(line, static_cast<size_t>(n));
  }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int n = std::snprintf(line, sizeof line, "f %d %d %d\n", mesh.F(f, 0) + 1, mesh.F(f, 1) + 1, mesh.F(f, 2) + 1);
    out.append(line, static_cast<size_t>(n));
  }
  return out;
}

namespace {

bool sniff(std::string_view bytes, MeshFormat* format) {
  size_t i = 0;
  while (i < bytes.size() && (is_space(bytes[i]) || bytes[i] == '\n')) ++i;
  std::string_view rest = bytes.substr(i);
  auto starts = [&](std::string_view prefix) { return rest.substr(0, prefix.size()) == prefix; };
  if (starts("ply") && (rest.size() == 3 || rest[3] == '\n' || rest[3] == '\r')) *format = MeshFormat::Ply;
  else if (starts("OFF") || starts("COFF") || starts("NOFF") || starts("CNOFF") || starts("STOFF"))
    *format = MeshFormat::Off;
  else if (starts_with_solid(bytes) || (bytes.size() >= 84 && 84 + 50 * uint64_t(le32(bytes, 80)) == bytes.size()))
    *format = MeshFormat::Stl;
  else if (starts("v ") || starts("v\t") || starts("f ") || starts("#") || starts("o ") || starts("g ") ||
           starts("mtllib") || starts("vn ") || starts("vt "))
    *format = MeshFormat::Obj;
  else return false;
  return true;
}

}  // namespace

MeshFormat detect_mesh_format(std::string_view filename, std::string_view bytes) {
  const size_t dot = filename.rfind('.');
  if (dot != std::string_view::npos) {
    std::string_view ext = filename.substr(dot + 1);
    if (iequals(ext, "obj")) return MeshFormat::Obj;
    if (iequals(ext, "off")) return MeshFormat::Off;
    if (iequals(ext, "ply")) return MeshFormat::Ply;
    if (iequals(ext, "stl")) return MeshFormat::Stl;
  }
  MeshFormat format;
  if (sniff(bytes, &format)) return format;
  fail(quote(filename) +
       ": unknown mesh format (supported: .obj, .off, .ply, .stl), and the content is "
       "not recognisable as any of them");
}

Mesh read_mesh(std::string_view bytes, std::string_view filename) {
  const MeshFormat format = detect_mesh_format(filename, bytes);
  try {
    switch (format) {
      case MeshFormat::Obj: return read_obj(bytes);
      case MeshFormat::Off: return read_off(bytes);
      case MeshFormat::Ply: return read_ply(bytes);
      case MeshFormat::Stl: return read_stl(bytes);
    }
  } catch (const Error& e) {
    if (filename.empty()) throw;
    throw Error(e.code(), std::string(filename) + ": " + e.what());
  }
  fail("unreachable mesh format");
}

}  // namespace sd
