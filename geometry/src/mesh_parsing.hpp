// What the mesh readers (obj_, off_, ply_, stl_, vtp_mesh_reader.cpp) share, private to the
// geometry library: a cursor over the bytes that knows its line and says where it failed, number
// parsing with overflow and finiteness checks, and the soup builder that enforces the limits of
// mesh_file.hpp (vertices, triangles, indices in range) as it grows.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "filum/geometry/mesh_file.hpp"

namespace filum::geometry::mesh_parsing {

/// A word for a message: quoted, at most 40 characters, control bytes as \xNN.
std::string quoted(std::string_view word);
/// A number for a message, exactly and briefly ("%.17g": 8, 0.10000000000000001, 1e+300).
std::string numberText(double value);

/// A decimal integer (optional sign), the whole word; false on anything else or overflow.
bool parseInteger(std::string_view word, long long& value);
/// A decimal floating-point number (optional sign, exponent), the whole word; false on anything
/// else. "nan" and "inf" parse: finiteness is the builder's check.
bool parseNumber(std::string_view word, double& value);

/// Reading position in the bytes of a mesh, with the line number for messages. Lines end in LF,
/// CRLF or (unless `lone_cr_ends_line` is false: PLY's binary data may follow a CR) a lone CR;
/// words are runs of anything but spaces, tabs, vertical tabs, form feeds and line ends.
class Cursor {
 public:
  /// `first_line`: the line number of the first byte (a cursor over one line of another).
  Cursor(std::string_view bytes, const std::string& name, bool lone_cr_ends_line = true, long first_line = 1)
      : bytes_(bytes), name_(name), lone_cr_ends_line_(lone_cr_ends_line), line_(first_line), word_line_(first_line) {}

  /// The next line, without its end; false at the end of the bytes.
  bool nextLine(std::string_view& line);
  /// The next word, across line ends; a word starting with `comment` (if not '\0') starts a
  /// comment to the end of its line, skipped. False at the end of the bytes.
  bool nextWord(std::string_view& word, char comment = '\0');
  /// Skips to the start of the next line (the rest of the current one is ignored).
  void skipRestOfLine();
  /// The next word, which must exist: fails "expected <what>, found the end of the file".
  std::string_view word(const std::string& what, char comment = '\0');
  /// The next word as a number / an integer: fails "expected <what>, found <word>".
  double number(const std::string& what, char comment = '\0');
  long long integer(const std::string& what, char comment = '\0');

  /// `count` raw bytes (binary data); fails at the end of the bytes.
  std::string_view take(std::size_t count, const std::string& what);

  std::size_t offset() const { return offset_; }
  std::size_t remaining() const { return bytes_.size() - offset_; }
  std::size_t size() const { return bytes_.size(); }
  /// The line of the last word or line read (1-based).
  long line() const { return word_line_; }

  const std::string& name() const { return name_; }
  /// From now on, fail() names the byte instead of the line (binary data).
  void placeByByte() { place_by_byte_ = true; }

  /// Throws std::runtime_error "name:line: expected <expected>, found <found>" (or failAtByte's
  /// message after placeByByte()).
  [[noreturn]] void fail(const std::string& expected, const std::string& found) const;
  /// Throws std::runtime_error "name: byte <offset>: expected <expected>, found <found>".
  [[noreturn]] void failAtByte(const std::string& expected, const std::string& found) const;

 private:
  bool atLineEnd() const;
  /// Steps over one line end at offset_ (LF, CRLF, CR) and counts it.
  void stepOverLineEnd();

  std::string_view bytes_;
  const std::string& name_;
  bool lone_cr_ends_line_;
  bool place_by_byte_ = false;
  std::size_t offset_ = 0;
  long line_;       // line of offset_
  long word_line_;  // line of the last word or line returned
};

/// Grows the soup under the limits of mesh_file.hpp. Messages go through the cursor (its place).
class SoupBuilder {
 public:
  explicit SoupBuilder(const Cursor& cursor) : cursor_(cursor) {}

  /// Before allocating for `count` announced vertices: at most kMaxMeshVertices.
  void expectVertices(long long count);
  /// A vertex; its coordinates must be finite.
  void addVertex(double x, double y, double z);
  /// A polygon of vertex indices in [0, vertexCount()), at least 3, fanned into triangles.
  void addPolygon(const std::vector<long long>& polygon);
  /// One triangle without the checks of addPolygon's indices (STL: indices made by the reader).
  void addTriangle(int a, int b, int c);

  long long vertexCount() const { return static_cast<long long>(vertices_.size() / 3); }
  /// The soup; fails if it has no triangle.
  PolygonSoup finish();

 private:
  const Cursor& cursor_;
  std::vector<double> vertices_;  // x, y, z of each vertex
  std::vector<int> triangles_;    // a, b, c of each triangle
};

PolygonSoup readObj(std::string_view bytes, const std::string& name);
PolygonSoup readOff(std::string_view bytes, const std::string& name);
PolygonSoup readPly(std::string_view bytes, const std::string& name);
PolygonSoup readStl(std::string_view bytes, const std::string& name);
PolygonSoup readVtp(std::string_view bytes, const std::string& name);

}  // namespace filum::geometry::mesh_parsing
