#include "core/mesh/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/error.h"

namespace sd {
namespace {

// ---------------------------------------------------------------------------------------------------
// Shared pieces: a growing mesh, fan triangulation, number parsing, line and token scanning.

// Collects vertices and triangles; polygons are fan-triangulated (a b c d -> a b c, a c d), the same
// convention as ../shared/data/SOURCES.md.
class MeshBuilder {
 public:
  void vertex(double x, double y, double z) {
    coords_.push_back(x);
    coords_.push_back(y);
    coords_.push_back(z);
  }
  int vertex_count() const { return static_cast<int>(coords_.size() / 3); }
  void polygon(const std::vector<int>& ids) {
    for (size_t k = 1; k + 1 < ids.size(); ++k) {
      triangles_.push_back(ids[0]);
      triangles_.push_back(ids[k]);
      triangles_.push_back(ids[k + 1]);
    }
  }
  size_t face_count() const { return triangles_.size() / 3; }
  Mesh build() const {
    Mesh mesh;
    mesh.V = Eigen::Map<const Vertices>(coords_.data(), static_cast<Eigen::Index>(coords_.size() / 3), 3);
    mesh.F = Eigen::Map<const Faces>(triangles_.data(), static_cast<Eigen::Index>(triangles_.size() / 3), 3);
    return mesh;
  }
  void reserve_vertices(size_t n) { coords_.reserve(3 * n); }

 private:
  std::vector<double> coords_;
  std::vector<int> triangles_;
};

// Throws the error with its location, e.g. "OBJ line 12: face index 9 is out of range".
[[noreturn]] void fail(const std::string& where, const std::string& what) { throw Error(where + ": " + what); }

std::string line_where(const char* format, size_t line) { return std::string(format) + " line " + std::to_string(line); }
std::string byte_where(const std::string& format, size_t offset) {
  return format + " byte offset " + std::to_string(offset);
}

// Quotes a token for a message, cutting long ones and showing control bytes as '?'.
std::string quote(std::string_view token) {
  std::string out = "'";
  size_t n = std::min<size_t>(token.size(), 40);
  for (size_t i = 0; i < n; ++i) {
    unsigned char c = static_cast<unsigned char>(token[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (token.size() > n) out += "...";
  return out + "'";
}

// A parsed number for a message: integers print as integers, anything (even 1e300 or NaN) is safe.
std::string number_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

// Full strtod syntax (also "nan", "inf", exponents); the whole token must be consumed.
bool parse_double(std::string_view token, double* out) {
  if (token.empty() || token.size() > 400) return false;
  char buffer[401];
  std::memcpy(buffer, token.data(), token.size());
  buffer[token.size()] = '\0';
  char* end = nullptr;
  *out = std::strtod(buffer, &end);
  return end == buffer + token.size();
}

// Decimal integer with optional sign; false on overflow or any other character.
bool parse_int64(std::string_view token, long long* out) {
  size_t i = 0;
  bool negative = false;
  if (i < token.size() && (token[i] == '+' || token[i] == '-')) negative = token[i++] == '-';
  if (i == token.size()) return false;
  unsigned long long value = 0;
  for (; i < token.size(); ++i) {
    if (token[i] < '0' || token[i] > '9') return false;
    value = value * 10 + static_cast<unsigned>(token[i] - '0');
    if (value > static_cast<unsigned long long>(LLONG_MAX)) return false;
  }
  *out = negative ? -static_cast<long long>(value) : static_cast<long long>(value);
  return true;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Splits one line (no '\n') into whitespace-separated tokens; text after `comment` is dropped.
void split(std::string_view line, char comment, std::vector<std::string_view>* tokens) {
  tokens->clear();
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    if (i >= line.size() || (comment && line[i] == comment)) break;
    size_t start = i;
    while (i < line.size() && !is_space(line[i]) && !(comment && line[i] == comment)) ++i;
    tokens->push_back(line.substr(start, i - start));
    if (i < line.size() && comment && line[i] == comment) break;
  }
}

// Walks the lines of a text buffer, counting from 1.
class LineReader {
 public:
  explicit LineReader(std::string_view text, size_t first_line = 1) : text_(text), next_line_(first_line) {}
  bool next(std::string_view* line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    *line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    number_ = next_line_++;
    return true;
  }
  size_t number() const { return number_; }
  size_t remaining_bytes() const { return pos_ >= text_.size() ? 0 : text_.size() - pos_; }

 private:
  std::string_view text_;
  size_t pos_ = 0;
  size_t next_line_;
  size_t number_ = 0;
};

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i])))
      return false;
  return true;
}

void require_faces(const MeshBuilder& builder, const char* format) {
  if (builder.face_count() == 0)
    throw Error(std::string(format) + ": the file has no faces (" + std::to_string(builder.vertex_count()) +
                " vertices); a triangle mesh is required");
}

// ---------------------------------------------------------------------------------------------------
// OBJ

// Keywords of the OBJ specification that carry nothing we need (texture/normal data, grouping,
// materials, free-form geometry, lines and points).
bool obj_ignored_keyword(std::string_view k) {
  static const char* const kIgnored[] = {"vt",     "vn",       "vp",       "o",         "g",       "s",
                                         "usemtl", "mtllib",   "l",        "p",         "cstype",  "deg",
                                         "bmat",   "step",     "curv",     "curv2",     "surf",    "parm",
                                         "trim",   "hole",     "scrv",     "sp",        "end",     "con",
                                         "mg",     "bevel",    "c_interp", "d_interp",  "lod",     "usemap",
                                         "maplib", "shadow_obj", "trace_obj", "ctech",  "stech",   "call",
                                         "csh",    "vc"};
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

// ---------------------------------------------------------------------------------------------------
// OFF

namespace {

// Next line with content (comments after '#' removed); false at the end of the text.
bool next_tokens(LineReader& lines, std::vector<std::string_view>* tokens) {
  std::string_view line;
  while (lines.next(&line)) {
    split(line, '#', tokens);
    if (!tokens->empty()) return true;
  }
  return false;
}

long long parse_count(std::string_view token, const std::string& where, const char* what) {
  long long value = 0;
  if (!parse_int64(token, &value)) fail(where, std::string(what) + " " + quote(token) + " is not an integer");
  if (value < 0) fail(where, std::string(what) + " " + std::to_string(value) + " is negative");
  return value;
}

}  // namespace

Mesh read_off(std::string_view bytes) {
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  if (!next_tokens(lines, &tokens)) throw Error("OFF: the file is empty");
  // Header keyword: [ST][C][N]OFF; the 4D and n-dimensional variants are not meshes in 3D.
  std::string_view magic = tokens[0];
  bool magic_ok = magic.size() >= 3 && magic.substr(magic.size() - 3) == "OFF";
  for (size_t i = 0; magic_ok && i + 3 < magic.size(); ++i)
    magic_ok = std::strchr("STCN", magic[i]) != nullptr;
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
      fail(line_where("OFF", lines.number() + 1), "the file ends after " + std::to_string(i) + " of " +
                                                      std::to_string(nv) + " vertices");
    const std::string where = line_where("OFF", lines.number());
    if (tokens.size() < 3) fail(where, "vertex needs 3 coordinates, found " + std::to_string(tokens.size()));
    double xyz[3];
    for (int a = 0; a < 3; ++a)
      if (!parse_double(tokens[a], &xyz[a]))
        fail(where, "vertex coordinate " + quote(tokens[a]) + " is not a number");
    builder.vertex(xyz[0], xyz[1], xyz[2]);
  }
  std::vector<int> polygon;
  for (long long f = 0; f < nf; ++f) {
    if (!next_tokens(lines, &tokens))
      fail(line_where("OFF", lines.number() + 1), "the file ends after " + std::to_string(f) + " of " +
                                                      std::to_string(nf) + " faces");
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

// ---------------------------------------------------------------------------------------------------
// PLY

namespace {

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

bool ply_type(std::string_view name, PlyType* type) {
  struct Entry {
    const char* name;
    PlyType type;
  };
  static const Entry kTypes[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
      {"uint8", PlyType::Uint8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::Uint16}, {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const Entry& e : kTypes)
    if (name == e.name) {
      *type = e.type;
      return true;
    }
  return false;
}

size_t ply_size(PlyType t) {
  switch (t) {
    case PlyType::Int8:
    case PlyType::Uint8: return 1;
    case PlyType::Int16:
    case PlyType::Uint16: return 2;
    case PlyType::Int32:
    case PlyType::Uint32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 1;
}

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // item type for lists
  bool is_list = false;
  PlyType count_type = PlyType::Uint8;
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittle, BinaryBig };

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  size_t data_offset = 0;  // first byte after "end_header\n"
  size_t data_line = 0;    // line number of the first data line (ASCII)
};

PlyHeader parse_ply_header(std::string_view bytes) {
  PlyHeader header;
  LineReader lines(bytes);
  std::vector<std::string_view> tokens;
  std::string_view line;
  bool has_format = false;
  size_t consumed = 0;
  bool first = true;
  while (true) {
    if (!lines.next(&line)) throw Error("PLY: the header has no 'end_header' line");
    consumed += line.size() + 1;
    const std::string where = line_where("PLY", lines.number());
    split(line, 0, &tokens);
    if (first) {
      if (tokens.size() != 1 || tokens[0] != "ply") fail(where, "expected the magic line 'ply'");
      first = false;
      continue;
    }
    if (tokens.empty()) continue;
    std::string_view key = tokens[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") break;
    if (key == "format") {
      if (tokens.size() < 3) fail(where, "expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (tokens[1] == "ascii") header.format = PlyFormat::Ascii;
      else if (tokens[1] == "binary_little_endian") header.format = PlyFormat::BinaryLittle;
      else if (tokens[1] == "binary_big_endian") header.format = PlyFormat::BinaryBig;
      else fail(where, "unknown format " + quote(tokens[1]));
      has_format = true;
    } else if (key == "element") {
      if (tokens.size() != 3) fail(where, "expected 'element <name> <count>'");
      PlyElement element;
      element.name = std::string(tokens[1]);
      element.count = parse_count(tokens[2], where, "element count");
      header.elements.push_back(element);
    } else if (key == "property") {
      if (header.elements.empty()) fail(where, "property before any element");
      PlyProperty property;
      if (tokens.size() >= 2 && tokens[1] == "list") {
        if (tokens.size() != 5) fail(where, "expected 'property list <count type> <item type> <name>'");
        if (!ply_type(tokens[2], &property.count_type)) fail(where, "unknown type " + quote(tokens[2]));
        if (!ply_type(tokens[3], &property.type)) fail(where, "unknown type " + quote(tokens[3]));
        property.is_list = true;
        property.name = std::string(tokens[4]);
      } else {
        if (tokens.size() != 3) fail(where, "expected 'property <type> <name>'");
        if (!ply_type(tokens[1], &property.type)) fail(where, "unknown type " + quote(tokens[1]));
        property.name = std::string(tokens[2]);
      }
      header.elements.back().properties.push_back(property);
    } else {
      fail(where, "unknown header keyword " + quote(key));
    }
  }
  if (!has_format) throw Error("PLY: the header has no 'format' line");
  header.data_offset = std::min(consumed, bytes.size());
  header.data_line = lines.number() + 1;
  return header;
}

// Reads PLY values one at a time, from ASCII tokens or binary bytes, and says where it is.
class PlyData {
 public:
  PlyData(std::string_view bytes, const PlyHeader& header)
      : bytes_(bytes), pos_(header.data_offset), format_(header.format), line_(header.data_line) {}

  // Value of the given type as a double (exact for every PLY type).
  double read(PlyType type) {
    if (format_ == PlyFormat::Ascii) return read_ascii(type);
    return read_binary(type);
  }

  std::string where() const {
    if (format_ == PlyFormat::Ascii) return line_where("PLY", line_);
    return byte_where(format_ == PlyFormat::BinaryLittle ? "PLY (binary_little_endian)" : "PLY (binary_big_endian)",
                      value_offset_);
  }
  size_t remaining() const { return bytes_.size() - std::min(pos_, bytes_.size()); }
  bool binary() const { return format_ != PlyFormat::Ascii; }

 private:
  double read_ascii(PlyType type) {
    while (pos_ < bytes_.size() && (is_space(bytes_[pos_]) || bytes_[pos_] == '\n')) {
      if (bytes_[pos_] == '\n') ++line_;
      ++pos_;
    }
    if (pos_ >= bytes_.size()) fail(line_where("PLY", line_), "the file ends in the middle of the data");
    size_t start = pos_;
    while (pos_ < bytes_.size() && !is_space(bytes_[pos_]) && bytes_[pos_] != '\n') ++pos_;
    std::string_view token = bytes_.substr(start, pos_ - start);
    double value = 0;
    if (!parse_double(token, &value)) fail(line_where("PLY", line_), quote(token) + " is not a number");
    if (type != PlyType::Float32 && type != PlyType::Float64 && value != std::floor(value))
      fail(line_where("PLY", line_), quote(token) + " is not an integer");
    return value;
  }

  double read_binary(PlyType type) {
    const size_t size = ply_size(type);
    value_offset_ = pos_;
    if (remaining() < size) fail(where(), "the file is truncated (a value needs " + std::to_string(size) + " bytes)");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, size);
    pos_ += size;
    if (format_ == PlyFormat::BinaryBig) std::reverse(b, b + size);  // the host is little endian
    switch (type) {
      case PlyType::Int8: return static_cast<int8_t>(b[0]);
      case PlyType::Uint8: return b[0];
      case PlyType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Uint16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
      case PlyType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Uint32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
      case PlyType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

  std::string_view bytes_;
  size_t pos_;
  PlyFormat format_;
  size_t line_;
  size_t value_offset_ = 0;
};

// Fewest bytes one instance of the element can occupy: a guard against declared counts that the
// file cannot hold (checked before anything is allocated or looped over).
double min_instance_bytes(const PlyElement& element, bool binary) {
  double bytes = 0;
  for (const PlyProperty& p : element.properties)
    bytes += binary ? static_cast<double>(ply_size(p.is_list ? p.count_type : p.type)) : 2.0;  // "0 "
  return bytes;
}

long long list_count(PlyData& data, PlyType type, size_t item_size) {
  double value = data.read(type);
  if (!(value >= 0) || value != std::floor(value))
    fail(data.where(), "list length " + number_text(value) + " is not a non-negative integer");
  const double most = data.binary() ? static_cast<double>(data.remaining() / item_size)
                                    : static_cast<double>(data.remaining() / 2 + 1);
  if (value > most)
    fail(data.where(), "list length " + number_text(value) +
                           " exceeds what the remaining " + std::to_string(data.remaining()) + " bytes can hold");
  return static_cast<long long>(value);
}

}  // namespace

Mesh read_ply(std::string_view bytes) {
  const PlyHeader header = parse_ply_header(bytes);
  const bool binary = header.format != PlyFormat::Ascii;
  // Declared counts against the bytes that follow the header.
  double needed = 0;
  long long vertex_count = -1;
  for (const PlyElement& e : header.elements) {
    needed += static_cast<double>(e.count) * min_instance_bytes(e, binary);
    if (e.name == "vertex") vertex_count = e.count;
  }
  const size_t available = bytes.size() - header.data_offset;
  if (needed > static_cast<double>(available) + 1)
    throw Error("PLY: the header declares elements needing at least " + number_text(needed) +
                " bytes of data, but only " + std::to_string(available) + " bytes follow the header (byte offset " +
                std::to_string(header.data_offset) + ")");
  if (vertex_count < 0) throw Error("PLY: the header has no 'vertex' element");
  if (vertex_count >= INT_MAX) throw Error("PLY: too many vertices (" + std::to_string(vertex_count) + ")");

  MeshBuilder builder;
  builder.reserve_vertices(static_cast<size_t>(vertex_count));
  PlyData data(bytes, header);
  std::vector<int> polygon;
  bool seen_faces = false;
  for (const PlyElement& e : header.elements) {
    if (e.properties.empty()) continue;  // nothing stored per instance
    const bool is_vertex = e.name == "vertex";
    const bool is_face = e.name == "face";
    int axis_of[3] = {-1, -1, -1};  // property index of x, y, z
    int index_property = -1;
    for (size_t p = 0; p < e.properties.size(); ++p) {
      const PlyProperty& prop = e.properties[p];
      if (is_vertex && !prop.is_list && prop.name.size() == 1 && prop.name[0] >= 'x' && prop.name[0] <= 'z')
        axis_of[prop.name[0] - 'x'] = static_cast<int>(p);
      if (is_face && prop.is_list && (prop.name == "vertex_indices" || prop.name == "vertex_index"))
        index_property = static_cast<int>(p);
    }
    if (is_vertex && (axis_of[0] < 0 || axis_of[1] < 0 || axis_of[2] < 0))
      throw Error("PLY: the vertex element needs scalar properties x, y and z");
    if (is_face && index_property < 0)
      throw Error("PLY: the face element has no list property 'vertex_indices' or 'vertex_index'");
    seen_faces = seen_faces || is_face;
    for (long long i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
      for (size_t p = 0; p < e.properties.size(); ++p) {
        const PlyProperty& prop = e.properties[p];
        if (!prop.is_list) {
          double value = data.read(prop.type);
          for (int a = 0; a < 3; ++a)
            if (is_vertex && axis_of[a] == static_cast<int>(p)) xyz[a] = value;
          continue;
        }
        const long long k = list_count(data, prop.count_type, ply_size(prop.type));
        const bool indices = is_face && index_property == static_cast<int>(p);
        if (indices && k < 3)
          fail(data.where(), "face has " + std::to_string(k) + " vertices; at least 3 are required");
        if (indices) polygon.clear();
        for (long long j = 0; j < k; ++j) {
          double value = data.read(prop.type);
          if (!indices) continue;
          if (!(value >= 0 && value < static_cast<double>(vertex_count)) || value != std::floor(value))
            fail(data.where(), "face index " + number_text(value) + " is out of range (" +
                                   std::to_string(vertex_count) + " vertices)");
          polygon.push_back(static_cast<int>(value));
        }
        if (indices) builder.polygon(polygon);
      }
      if (is_vertex) builder.vertex(xyz[0], xyz[1], xyz[2]);
    }
  }
  if (!seen_faces) throw Error("PLY: the header has no 'face' element; a triangle mesh is required");
  require_faces(builder, "PLY");
  return builder.build();
}

// ---------------------------------------------------------------------------------------------------
// STL

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

bool starts_with_solid(std::string_view bytes) {
  size_t i = 0;
  while (i < bytes.size() && (is_space(bytes[i]) || bytes[i] == '\n')) ++i;
  return bytes.size() - i >= 5 && iequals(bytes.substr(i, 5), "solid") &&
         (bytes.size() - i == 5 || is_space(bytes[i + 5]) || bytes[i + 5] == '\n');
}

bool looks_textual(std::string_view bytes) {
  for (char ch : bytes.substr(0, std::min<size_t>(bytes.size(), 512))) {
    unsigned char c = static_cast<unsigned char>(ch);
    if (c < 32 && !(c == '\n' || c == '\r' || c == '\t' || c == '\f' || c == '\v')) return false;  // UTF-8 names pass
  }
  return true;
}

uint32_t le32(std::string_view bytes, size_t at) {
  const unsigned char* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
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
    fail(byte_where(format, bytes.size()), "truncated: the 80-byte header and the triangle count need 84 bytes, "
                                           "the file has " + std::to_string(bytes.size()));
  const uint64_t count = le32(bytes, 80);
  const uint64_t needed = 84 + 50 * count;
  if (needed > bytes.size())
    fail(byte_where(format, 80), "declares " + std::to_string(count) + " triangles, which need " +
                                     std::to_string(needed) + " bytes, but the file has " + std::to_string(bytes.size()));
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

Mesh read_stl(std::string_view bytes) {
  return stl_is_binary(bytes) ? read_binary_stl(bytes) : read_ascii_stl(bytes);
}

// ---------------------------------------------------------------------------------------------------
// Writer, format detection, dispatch

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
  else
    return false;
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
  throw Error(quote(filename) + ": unknown mesh format (supported: .obj, .off, .ply, .stl), and the content is "
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
    throw Error(std::string(filename) + ": " + e.what());
  }
  throw Error("unreachable mesh format");
}

}  // namespace sd
