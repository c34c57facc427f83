// Reading and writing triangle meshes from memory buffers (the browser has no file system).
// Formats: OBJ (polygons fan-triangulated, negative indices, comments; vt/vn/materials ignored), OFF,
// PLY (ASCII, binary little and big endian), STL (ASCII and binary; coincident vertices welded).
// Every error is an sd::Error whose message names the format and the line (text) or byte offset (binary),
// e.g. "OBJ line 12: face index 9 is out of range (8 vertices)"; a file with no faces is an error.
// NaN/inf coordinates are returned as read: check_mesh reports them. Declared counts (OFF, PLY, binary
// STL) are checked against the bytes that follow before anything is allocated.
// Details: OBJ keeps v/f (f entries i, i/t, i//n, i/t/n; negative = relative; faces may name vertices
// defined later) and ignores the other keywords of the OBJ spec; an unknown keyword is an error (it is
// usually a binary or misnamed file). OFF accepts [ST][C][N]OFF, counts on the header line or the next,
// extra values after coordinates/indices (colours) ignored. PLY: x, y, z of any scalar type, other
// properties and elements skipped, faces from the list "vertex_indices" or "vertex_index" (any count and
// index type). STL is ASCII when it starts with "solid" and its first 512 bytes contain no control
// bytes, else binary (binary headers often start with "solid" too); exactly equal corners are welded
// (-0 and +0 alike), stored normals are ignored.
#pragma once

#include <string>
#include <string_view>

#include "core/mesh/mesh.h"

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
// Throws sd::Error (invalid_argument) naming the first vertex with a NaN or infinite coordinate.
std::string write_obj(const Mesh& mesh, std::string_view comment = {});

}  // namespace sd
