// Reading and writing triangle meshes from memory buffers (the browser has no file system).
// Formats: OBJ (polygons fan-triangulated, negative indices, comments; vt/vn/materials ignored), OFF,
// PLY (ASCII, binary little and big endian), STL (ASCII and binary; coincident vertices welded).
// Every error is an sd::Error whose message names the format and the line (text) or byte offset (binary).
#pragma once

#include <string>
#include <string_view>

#include "core/mesh.h"

namespace sd {

enum class MeshFormat { Obj, Off, Ply, Stl };

// Format from the file name's extension (case-insensitive); when the name has no known extension the
// content is sniffed. Throws sd::Error when neither identifies a supported format.
MeshFormat detect_mesh_format(std::string_view filename, std::string_view bytes);

// Parses `bytes` as a mesh; `filename` is used for the format and in error messages.
Mesh read_mesh(std::string_view bytes, std::string_view filename);

Mesh read_obj(std::string_view bytes);
Mesh read_off(std::string_view bytes);
Mesh read_ply(std::string_view bytes);
Mesh read_stl(std::string_view bytes);

// OBJ text with full double precision (round-trips exactly). `comment` lines are prefixed with "# ".
std::string write_obj(const Mesh& mesh, std::string_view comment = {});

}  // namespace sd
