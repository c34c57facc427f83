// The PLY reader of mesh_io.h (format details there).
#include "core/mesh/mesh_io.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "core/mesh/internal/mesh_parsing.h"

namespace sd {

using namespace parsing;

namespace {

enum class PlyType { Int8, Uint8, Int16, Uint16, Int32, Uint32, Float32, Float64 };

bool ply_type(std::string_view name, PlyType* type) {
  struct Entry {
    const char* name;
    PlyType type;
  };
  static const Entry kTypes[] = {
      {"char", PlyType::Int8},      {"int8", PlyType::Int8},       {"uchar", PlyType::Uint8},
      {"uint8", PlyType::Uint8},    {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::Uint16},  {"uint16", PlyType::Uint16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},    {"uint", PlyType::Uint32},     {"uint32", PlyType::Uint32},
      {"float", PlyType::Float32},  {"float32", PlyType::Float32}, {"double", PlyType::Float64},
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
    if (!lines.next(&line)) fail("PLY: the header has no 'end_header' line");
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
  if (!has_format) fail("PLY: the header has no 'format' line");
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
      case PlyType::Int16: {
        int16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::Uint16: {
        uint16_t v;
        std::memcpy(&v, b, 2);
        return v;
      }
      case PlyType::Int32: {
        int32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::Uint32: {
        uint32_t v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::Float32: {
        float v;
        std::memcpy(&v, b, 4);
        return v;
      }
      case PlyType::Float64: {
        double v;
        std::memcpy(&v, b, 8);
        return v;
      }
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
  const double most =
      data.binary() ? static_cast<double>(data.remaining() / item_size) : static_cast<double>(data.remaining() / 2 + 1);
  if (value > most)
    fail(data.where(), "list length " + number_text(value) + " exceeds what the remaining " +
                           std::to_string(data.remaining()) + " bytes can hold");
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
    fail("PLY: the header declares elements needing at least " + number_text(needed) + " bytes of data, but only " +
         std::to_string(available) + " bytes follow the header (byte offset " + std::to_string(header.data_offset) +
         ")");
  if (vertex_count < 0) fail("PLY: the header has no 'vertex' element");
  if (vertex_count >= INT_MAX) fail("PLY: too many vertices (" + std::to_string(vertex_count) + ")");

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
      fail("PLY: the vertex element needs scalar properties x, y and z");
    if (is_face && index_property < 0)
      fail("PLY: the face element has no list property 'vertex_indices' or 'vertex_index'");
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
  if (!seen_faces) fail("PLY: the header has no 'face' element; a triangle mesh is required");
  require_faces(builder, "PLY");
  return builder.build();
}

}  // namespace sd
