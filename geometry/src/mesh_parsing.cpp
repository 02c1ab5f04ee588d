#include "mesh_parsing.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace filum::geometry::mesh_parsing {

std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string quoted(std::string_view word) {
  constexpr std::size_t kShown = 40;
  std::string text = "\"";
  for (std::size_t i = 0; i < word.size() && i < kShown; ++i) {
    const auto c = static_cast<unsigned char>(word[i]);
    if (c < 0x20 || c >= 0x7f || c == '"' || c == '\\') {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      text += escaped;
    } else {
      text += static_cast<char>(c);
    }
  }
  if (word.size() > kShown) text += "...";
  return text + "\"";
}

namespace {

// "+1" as "1"; false for "", "+", "+-1".
bool dropPlusSign(std::string_view& word) {
  const bool plus = !word.empty() && word.front() == '+';
  if (plus) word.remove_prefix(1);
  return !word.empty() && !(plus && word.front() == '-');
}

}  // namespace

bool parseInteger(std::string_view word, long long& value) {
  if (!dropPlusSign(word)) return false;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

bool parseNumber(std::string_view word, double& value) {
  if (!dropPlusSign(word)) return false;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  return error == std::errc() && end == word.data() + word.size();
}

namespace {

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

}  // namespace

bool Cursor::atLineEnd() const {
  const char c = bytes_[offset_];
  return c == '\n' || (c == '\r' && (lone_cr_ends_line_ || (offset_ + 1 < bytes_.size() && bytes_[offset_ + 1] == '\n')));
}

void Cursor::stepOverLineEnd() {
  if (bytes_[offset_] == '\r' && offset_ + 1 < bytes_.size() && bytes_[offset_ + 1] == '\n') ++offset_;
  ++offset_;
  ++line_;
}

bool Cursor::nextLine(std::string_view& line) {
  if (offset_ >= bytes_.size()) return false;
  const std::size_t start = offset_;
  while (offset_ < bytes_.size() && !atLineEnd()) ++offset_;
  line = bytes_.substr(start, offset_ - start);
  word_line_ = line_;
  if (offset_ < bytes_.size()) stepOverLineEnd();
  return true;
}

bool Cursor::nextWord(std::string_view& word, char comment) {
  while (offset_ < bytes_.size()) {
    if (isBlank(bytes_[offset_])) {
      ++offset_;
    } else if (atLineEnd()) {
      stepOverLineEnd();
    } else if (comment != '\0' && bytes_[offset_] == comment) {
      while (offset_ < bytes_.size() && !atLineEnd()) ++offset_;
    } else {
      const std::size_t start = offset_;
      while (offset_ < bytes_.size() && !isBlank(bytes_[offset_]) && !atLineEnd()) ++offset_;
      word = bytes_.substr(start, offset_ - start);
      word_line_ = line_;
      return true;
    }
  }
  word_line_ = line_;
  return false;
}

void Cursor::skipRestOfLine() {
  while (offset_ < bytes_.size() && !atLineEnd()) ++offset_;
  if (offset_ < bytes_.size()) stepOverLineEnd();
}

std::string_view Cursor::word(const std::string& what, char comment) {
  std::string_view w;
  if (!nextWord(w, comment)) fail(what, "the end of the file");
  return w;
}

double Cursor::number(const std::string& what, char comment) {
  const std::string_view w = word(what, comment);
  double value = 0.0;
  if (!parseNumber(w, value)) fail(what, quoted(w));
  return value;
}

long long Cursor::integer(const std::string& what, char comment) {
  const std::string_view w = word(what, comment);
  long long value = 0;
  if (!parseInteger(w, value)) fail(what, quoted(w));
  return value;
}

std::string_view Cursor::take(std::size_t count, const std::string& what) {
  if (count > remaining())
    failAtByte(what + " (" + std::to_string(count) + " bytes)",
               "the end of the file after " + std::to_string(remaining()) + " bytes");
  const std::string_view taken = bytes_.substr(offset_, count);
  offset_ += count;
  return taken;
}

void Cursor::fail(const std::string& expected, const std::string& found) const {
  if (place_by_byte_) failAtByte(expected, found);
  throw std::runtime_error(name_ + ":" + std::to_string(word_line_) + ": expected " + expected + ", found " + found);
}

void Cursor::failAtByte(const std::string& expected, const std::string& found) const {
  throw std::runtime_error(name_ + ": byte " + std::to_string(offset_) + ": expected " + expected + ", found " + found);
}

void SoupBuilder::expectVertices(long long count) {
  if (count < 0 || count > kMaxMeshVertices)
    cursor_.fail("a vertex count in [0, " + std::to_string(kMaxMeshVertices) + "] (mesh_file.hpp)",
                 std::to_string(count));
  vertices_.reserve(static_cast<std::size_t>(3 * count));
}

void SoupBuilder::addVertex(double x, double y, double z) {
  if (vertexCount() >= kMaxMeshVertices)
    cursor_.fail("at most " + std::to_string(kMaxMeshVertices) + " vertices (mesh_file.hpp)", "one more");
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
    char text[96];
    std::snprintf(text, sizeof text, "(%g, %g, %g)", x, y, z);
    cursor_.fail("a vertex of finite coordinates", text);
  }
  vertices_.insert(vertices_.end(), {x, y, z});
}

void SoupBuilder::addPolygon(const std::vector<long long>& polygon) {
  if (polygon.size() < 3) cursor_.fail("a face of at least 3 vertices", std::to_string(polygon.size()));
  for (const long long index : polygon)
    if (index < 0 || index >= vertexCount())
      cursor_.fail("vertex indices in [0, " + std::to_string(vertexCount()) + ") (the vertices so far)",
                   "index " + std::to_string(index));
  const auto triangles = static_cast<long long>(triangles_.size() / 3);
  if (triangles + static_cast<long long>(polygon.size()) - 2 > kMaxMeshTriangles)
    cursor_.fail("at most " + std::to_string(kMaxMeshTriangles) + " triangles (mesh_file.hpp)",
                 "more in a face of " + std::to_string(polygon.size()) + " vertices");
  // Fanned: (v0, v_k, v_{k+1}).
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
    triangles_.insert(triangles_.end(), {static_cast<int>(polygon[0]), static_cast<int>(polygon[k]),
                                         static_cast<int>(polygon[k + 1])});
}

void SoupBuilder::addTriangle(int a, int b, int c) {
  if (static_cast<long long>(triangles_.size() / 3) >= kMaxMeshTriangles)
    cursor_.fail("at most " + std::to_string(kMaxMeshTriangles) + " triangles (mesh_file.hpp)", "one more");
  triangles_.insert(triangles_.end(), {a, b, c});
}

PolygonSoup SoupBuilder::finish() {
  if (triangles_.empty()) cursor_.fail("at least one face", "none");
  PolygonSoup soup;
  soup.vertices = Eigen::Map<const Points>(vertices_.data(), static_cast<Eigen::Index>(vertices_.size() / 3), 3);
  soup.triangles =
      Eigen::Map<const TriangleIndices>(triangles_.data(), static_cast<Eigen::Index>(triangles_.size() / 3), 3);
  return soup;
}

}  // namespace filum::geometry::mesh_parsing
