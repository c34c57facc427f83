// What the mesh readers (mesh_io.h: OBJ, OFF, PLY, STL, one file each under internal/) share: a growing
// mesh with fan triangulation, parse errors that say where, number parsing, and line and token scanning.
// Private to cpp/core/mesh.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.h"

namespace sd::parsing {

// Collects vertices and triangles; polygons are fan-triangulated (a b c d -> a b c, a c d), the
// usual convention of mesh files.
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

// Throws sd::Error (ErrorCode::ParseError) "where: what", e.g. "OBJ line 12: face index 9 is out of range".
[[noreturn]] void fail(const std::string& where, const std::string& what);
[[noreturn]] void fail(const std::string& message);
std::string line_where(const char* format, size_t line);           // "OBJ line 12"
std::string byte_where(const std::string& format, size_t offset);  // "STL (binary) byte offset 80"

// Quotes a token for a message, cutting long ones and showing control bytes as '?'.
std::string quote(std::string_view token);
// A parsed number for a message: integers print as integers, anything (even 1e300 or NaN) is safe.
std::string number_text(double v);

// Full strtod syntax (also "nan", "inf", exponents); the whole token must be consumed.
bool parse_double(std::string_view token, double* out);
// Decimal integer with optional sign; false on overflow or any other character.
bool parse_int64(std::string_view token, long long* out);
// A non-negative integer count from a header; fails naming `what` otherwise.
long long parse_count(std::string_view token, const std::string& where, const char* what);

bool is_space(char c);                                 // space, tab, CR, FF, VT (not '\n': lines are split first)
bool iequals(std::string_view a, std::string_view b);  // ASCII case-insensitive
// Splits one line (no '\n') into whitespace-separated tokens; text after `comment` is dropped.
void split(std::string_view line, char comment, std::vector<std::string_view>* tokens);

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

// Next line with content (comments after '#' removed) into `tokens`; false at the end of the text.
bool next_tokens(LineReader& lines, std::vector<std::string_view>* tokens);

// Fails when the builder has no faces: every reader requires a triangle mesh.
void require_faces(const MeshBuilder& builder, const char* format);

// STL facts the format detection also needs: an ASCII STL starts with "solid" (after whitespace);
// a binary STL stores its triangle count as a little-endian uint32 at byte 80.
bool starts_with_solid(std::string_view bytes);
uint32_t le32(std::string_view bytes, size_t at);

}  // namespace sd::parsing
