#include "core/mesh/internal/mesh_parsing.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/error.h"

namespace sd::parsing {

void fail(const std::string& where, const std::string& what) { fail(where + ": " + what); }
void fail(const std::string& message) { throw Error(ErrorCode::ParseError, message); }

std::string line_where(const char* format, size_t line) {
  return std::string(format) + " line " + std::to_string(line);
}
std::string byte_where(const std::string& format, size_t offset) {
  return format + " byte offset " + std::to_string(offset);
}

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

std::string number_text(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

bool parse_double(std::string_view token, double* out) {
  if (token.empty() || token.size() > 400) return false;
  char buffer[401];
  std::memcpy(buffer, token.data(), token.size());
  buffer[token.size()] = '\0';
  char* end = nullptr;
  *out = std::strtod(buffer, &end);
  return end == buffer + token.size();
}

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

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

void require_faces(const MeshBuilder& builder, const char* format) {
  if (builder.face_count() == 0)
    fail(std::string(format) + ": the file has no faces (" + std::to_string(builder.vertex_count()) +
         " vertices); a triangle mesh is required");
}

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

bool starts_with_solid(std::string_view bytes) {
  size_t i = 0;
  while (i < bytes.size() && (is_space(bytes[i]) || bytes[i] == '\n')) ++i;
  return bytes.size() - i >= 5 && iequals(bytes.substr(i, 5), "solid") &&
         (bytes.size() - i == 5 || is_space(bytes[i + 5]) || bytes[i + 5] == '\n');
}

uint32_t le32(std::string_view bytes, size_t at) {
  const unsigned char* b = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
  return uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
}

}  // namespace sd::parsing
