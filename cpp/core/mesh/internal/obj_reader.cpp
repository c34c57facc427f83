// The OBJ reader of mesh_io.h (format details there).
#include "core/mesh/mesh_io.h"

#include <algorithm>
#include <climits>
#include <string>
#include <vector>

#include "core/mesh/internal/mesh_parsing.h"

namespace sd {

using namespace parsing;

namespace {

// Keywords of the OBJ specification that carry nothing we need (texture/normal data, grouping,
// materials, free-form geometry, lines and points).
bool obj_ignored_keyword(std::string_view k) {
  static const char* const kIgnored[] = {
      "vt",     "vn",         "vp",        "o",     "g",     "s",     "usemtl",   "mtllib",   "l",    "p",
      "cstype", "deg",        "bmat",      "step",  "curv",  "curv2", "surf",     "parm",     "trim", "hole",
      "scrv",   "sp",         "end",       "con",   "mg",    "bevel", "c_interp", "d_interp", "lod",  "usemap",
      "maplib", "shadow_obj", "trace_obj", "ctech", "stech", "call",  "csh",      "vc"};
  for (const char* ignored : kIgnored)
    if (k == ignored) return true;
  return false;
}

}  // namespace

Mesh read_obj(std::string_view bytes) {
  MeshBuilder builder;
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::vector<int> polygon;
  // Positive indices may name vertices defined further down; those are checked once all are read.
  struct Pending {
    long long index;
    size_t line;
  };
  std::vector<Pending> forward;
  std::string_view line;
  while (lines.next(&line)) {
    split(line, '#', &tokens);
    if (tokens.empty()) continue;
    const size_t n = lines.number();
    std::string_view key = tokens[0];
    if (key == "v") {
      if (tokens.size() < 4)
        fail(line_where("OBJ", n), "vertex needs 3 coordinates, found " + std::to_string(tokens.size() - 1));
      double xyz[3];
      for (int a = 0; a < 3; ++a)
        if (!parse_double(tokens[a + 1], &xyz[a]))
          fail(line_where("OBJ", n), "vertex coordinate " + quote(tokens[a + 1]) + " is not a number");
      if (builder.vertex_count() == INT_MAX) fail(line_where("OBJ", n), "too many vertices");
      builder.vertex(xyz[0], xyz[1], xyz[2]);
    } else if (key == "f") {
      if (tokens.size() < 4)
        fail(line_where("OBJ", n),
             "face has " + std::to_string(tokens.size() - 1) + " vertices; at least 3 are required");
      polygon.clear();
      for (size_t k = 1; k < tokens.size(); ++k) {
        std::string_view entry = tokens[k];
        std::string_view index_text = entry.substr(0, entry.find('/'));  // "3", "3/1", "3//2", "3/1/2"
        long long index = 0;
        if (!parse_int64(index_text, &index))
          fail(line_where("OBJ", n), "face entry " + quote(entry) + " is not a vertex index");
        const long long count = builder.vertex_count();
        long long id = 0;
        if (index == 0) {
          fail(line_where("OBJ", n), "face index 0 is invalid (OBJ indices start at 1)");
        } else if (index < 0) {  // relative: -1 is the last vertex defined so far
          id = count + index;
          if (id < 0)
            fail(line_where("OBJ", n), "face index " + std::to_string(index) + " is out of range (only " +
                                           std::to_string(count) + " vertices defined so far)");
        } else {
          id = index - 1;
          if (id >= INT_MAX) fail(line_where("OBJ", n), "face index " + std::to_string(index) + " is out of range");
          if (id >= count) forward.push_back({index, n});
        }
        polygon.push_back(static_cast<int>(id));
      }
      builder.polygon(polygon);
    } else if (!obj_ignored_keyword(key)) {
      fail(line_where("OBJ", n), "unknown keyword " + quote(key));
    }
  }
  for (const Pending& p : forward)
    if (p.index > builder.vertex_count())
      fail(line_where("OBJ", p.line), "face index " + std::to_string(p.index) + " is out of range (the file has " +
                                          std::to_string(builder.vertex_count()) + " vertices)");
  require_faces(builder, "OBJ");
  return builder.build();
}

}  // namespace sd
