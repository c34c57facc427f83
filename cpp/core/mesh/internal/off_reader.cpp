// The OFF reader of mesh_io.h (format details there).
#include "core/mesh/mesh_io.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <string>
#include <vector>

#include "core/mesh/internal/mesh_parsing.h"

namespace sd {

using namespace parsing;

Mesh read_off(std::string_view bytes) {
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  if (!next_tokens(lines, &tokens)) fail("OFF: the file is empty");
  // Header keyword: [ST][C][N]OFF; the 4D and n-dimensional variants are not meshes in 3D.
  std::string_view magic = tokens[0];
  bool magic_ok = magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF";
  for (size_t i = 0; magic_ok && i + 3 < magic.size(); ++i) magic_ok = std::strchr("STCN", magic[i]) != nullptr;
  if (!magic_ok) {
    if (magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF")
      fail(line_where("OFF", lines.number()), "unsupported OFF variant " + quote(magic) + " (only 3D OFF)");
    fail(line_where("OFF", lines.number()), "expected the header 'OFF', found " + quote(magic));
  }
  tokens.erase(tokens.begin());
  if (tokens.empty() && !next_tokens(lines, &tokens))
    fail(line_where("OFF", lines.number()), "the file ends before the vertex and face counts");
  const std::string counts_where = line_where("OFF", lines.number());
  if (tokens.size() < 2) fail(counts_where, "expected 'vertices faces edges' counts");
  const long long nv = parse_count(tokens[0], counts_where, "vertex count");
  const long long nf = parse_count(tokens[1], counts_where, "face count");
  if (nv >= INT_MAX || nf >= INT_MAX)
    fail(counts_where, "header declares " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
                           " faces, more than a mesh may have");
  MeshBuilder builder;
  // Declared counts are not trusted for allocation: a vertex line takes at least 6 bytes ("0 0 0\n"),
  // so never reserve more than the remaining bytes can hold; a short file is reported below.
  builder.reserve_vertices(std::min<size_t>(static_cast<size_t>(nv), lines.remaining_bytes() / 6 + 1));
  for (long long i = 0; i < nv; ++i) {
    if (!next_tokens(lines, &tokens))
      fail(line_where("OFF", lines.number() + 1),
           "the file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    const std::string where = line_where("OFF", lines.number());
    if (tokens.size() < 3) fail(where, "vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    double xyz[3];
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tokens[a], &xyz[a])) fail(where, "vertex coordinate " + quote(tokens[a]) + " is not a number");
    builder.vertex(xyz[0], xyz[1], xyz[2]);
  }
  std::vector<int> polygon;
  for (long long f = 0; f < nf; ++f) {
    if (!next_tokens(lines, &tokens))
      fail(line_where("OFF", lines.number() + 1),
           "the file ends after " + std::to_string(f) + " of " + std::to_string(nf) + " faces");
    const std::string where = line_where("OFF", lines.number());
    const long long k = parse_count(tokens[0], where, "face vertex count");
    if (k < 3) fail(where, "face has " + std::to_string(k) + " vertices; at least 3 are required");
    if (k > static_cast<long long>(tokens.size()) - 1)
      fail(where, "face declares " + std::to_string(k) + " vertices but the line has " +
                      std::to_string(tokens.size() - 1) + " indices");
    polygon.clear();
    for (long long j = 1; j <= k; ++j) {
      long long id = 0;
      if (!parse_int64(tokens[j], &id)) fail(where, "face index " + quote(tokens[j]) + " is not an integer");
      if (id < 0 || id >= nv)
        fail(where, "face index " + std::to_string(id) + " is out of range (" + std::to_string(nv) + " vertices)");
      polygon.push_back(static_cast<int>(id));
    }
    builder.polygon(polygon);  // values after the indices (face colours) are ignored
  }
  require_faces(builder, "OFF");
  return builder.build();
}

}  // namespace sd
