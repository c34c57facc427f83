// The STL reader of mesh_io.h (format details there).
#include "core/mesh/mesh_io.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/mesh/internal/mesh_parsing.h"

namespace sd {

using namespace parsing;

namespace {

// Welds exactly coincident corners (STL stores every triangle's corners separately).
class Welder {
 public:
  explicit Welder(MeshBuilder* builder) : builder_(builder) {}
  int vertex(double x, double y, double z) {
    // +0.0 turns -0.0 into 0.0 so that both weld; NaN corners weld only with identical bit patterns.
    Key key{bits(x + 0.0), bits(y + 0.0), bits(z + 0.0)};
    auto found = ids_.find(key);
    if (found != ids_.end()) return found->second;
    int id = builder_->vertex_count();
    builder_->vertex(x, y, z);
    ids_.emplace(key, id);
    return id;
  }

 private:
  struct Key {
    uint64_t x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = k.x * 0x9E3779B97F4A7C15ull;
      h ^= (k.y + 0x632BE59BD9B4E019ull + (h << 6) + (h >> 2));
      h ^= (k.z + 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2));
      return static_cast<size_t>(h ^ (h >> 29));
    }
  };
  static uint64_t bits(double v) {
    uint64_t u;
    std::memcpy(&u, &v, 8);
    return u;
  }
  MeshBuilder* builder_;
  std::unordered_map<Key, int, KeyHash> ids_;
};

bool looks_textual(std::string_view bytes) {
  for (char ch : bytes.substr(0, std::min<size_t>(bytes.size(), 512))) {
    unsigned char c = static_cast<unsigned char>(ch);
    if (c < 32 && !(c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v')) return false;  // UTF-8 names pass
  }
  return true;
}

float le_float(std::string_view bytes, size_t at) {
  uint32_t u = le32(bytes, at);
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

// ASCII when the file starts with "solid" and its first 512 bytes are text; otherwise binary. Many
// binary files also start with "solid", but their triangle count and float bytes soon bring control
// bytes (NUL in particular) that text never has. The 84 + 50 n size rule is not used to decide because
// some binary writers append bytes and truncated files must still be reported as binary.
bool stl_is_binary(std::string_view bytes) { return !(starts_with_solid(bytes) && looks_textual(bytes)); }

Mesh read_binary_stl(std::string_view bytes) {
  const std::string format = "STL (binary)";
  if (bytes.size() < 84)
    fail(byte_where(format, bytes.size()),
         "truncated: the 80-byte header and the triangle count need 84 bytes, "
         "the file has " +
             std::to_string(bytes.size()));
  const uint64_t count = le32(bytes, 80);
  const uint64_t needed = 84 + 50 * count;
  if (needed > bytes.size())
    fail(byte_where(format, 80), "declares " + std::to_string(count) + " triangles, which need " +
                                     std::to_string(needed) + " bytes, but the file has " +
                                     std::to_string(bytes.size()));
  MeshBuilder builder;
  Welder welder(&builder);
  std::vector<int> triangle(3);
  for (uint64_t t = 0; t < count; ++t) {
    const size_t at = 84 + 50 * t + 12;  // skip the stored normal: it is recomputed from the corners
    for (int c = 0; c < 3; ++c)
      triangle[c] = welder.vertex(le_float(bytes, at + 12 * c), le_float(bytes, at + 12 * c + 4),
                                  le_float(bytes, at + 12 * c + 8));
    builder.polygon(triangle);
  }
  require_faces(builder, "STL");
  return builder.build();
}

Mesh read_ascii_stl(std::string_view bytes) {
  MeshBuilder builder;
  Welder welder(&builder);
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::vector<int> polygon;
  // States of "solid / facet normal / outer loop / vertex* / endloop / endfacet / endsolid".
  enum class State { Solid, Facet, Loop, Vertex, EndFacet, Done } state = State::Solid;
  auto expect = [&](const char* what) {
    fail(line_where("STL", lines.number()), std::string("expected '") + what + "', found " + quote(tokens[0]));
  };
  while (next_tokens(lines, &tokens)) {
    const std::string_view key = tokens[0];
    switch (state) {
      case State::Solid:
      case State::Done:
        if (!iequals(key, "solid")) expect("solid");
        state = State::Facet;
        break;
      case State::Facet:
        if (iequals(key, "endsolid")) {
          state = State::Done;
        } else if (iequals(key, "facet")) {
          state = State::Loop;
        } else {
          expect("facet' or 'endsolid");
        }
        break;
      case State::Loop:
        if (!iequals(key, "outer") || tokens.size() < 2 || !iequals(tokens[1], "loop")) expect("outer loop");
        polygon.clear();
        state = State::Vertex;
        break;
      case State::Vertex:
        if (iequals(key, "vertex")) {
          if (tokens.size() < 4) fail(line_where("STL", lines.number()), "vertex needs 3 coordinates");
          double xyz[3];
          for (int a = 0; a < 3; ++a)
            if (!parse_double(tokens[a + 1], &xyz[a]))
              fail(line_where("STL", lines.number()), "vertex coordinate " + quote(tokens[a + 1]) + " is not a number");
          polygon.push_back(welder.vertex(xyz[0], xyz[1], xyz[2]));
        } else if (iequals(key, "endloop")) {
          if (polygon.size() < 3)
            fail(line_where("STL", lines.number()),
                 "facet has " + std::to_string(polygon.size()) + " vertices; at least 3 are required");
          builder.polygon(polygon);
          state = State::EndFacet;
        } else {
          expect("vertex' or 'endloop");
        }
        break;
      case State::EndFacet:
        if (!iequals(key, "endfacet")) expect("endfacet");
        state = State::Facet;
        break;
    }
  }
  // A missing final "endsolid" is tolerated; ending inside a facet means the file was cut short.
  if (state != State::Facet && state != State::Done)
    fail(line_where("STL", lines.number()), "the file ends in the middle of a facet");
  require_faces(builder, "STL");
  return builder.build();
}

}  // namespace

Mesh read_stl(std::string_view bytes) { return stl_is_binary(bytes) ? read_binary_stl(bytes) : read_ascii_stl(bytes); }

}  // namespace sd
