// STL (mesh_file.hpp; CAD tools, 3D printing, segmentation exports): triangles that each carry
// their three corners, ascii ("solid", "facet normal", "outer loop", "vertex x y z", "endloop",
// "endfacet", "endsolid") or binary (80-byte header, uint32 triangle count, then per triangle 12
// little-endian float32 — normal and corners — and a uint16 attribute). Corners with the same
// coordinates become one vertex: without it every triangle would be an island, and CGAL's inside
// test needs a closed surface. Triangles that merging collapses (two equal corners) are dropped.
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <vector>

#include "mesh_parsing.hpp"

namespace filum::geometry::mesh_parsing {

namespace {

// Vertex of given coordinates: an open-addressing hash table (linear probing, load <= 1/2) of
// vertex indices over the coordinates, growing by doubling: 8 bytes per vertex at most.
class VertexMerger {
 public:
  explicit VertexMerger(SoupBuilder& soup) : soup_(soup), table_(1024, -1) {}

  int index(double x, double y, double z) {
    // -0.0 and 0.0 are the same corner.
    x += 0.0;
    y += 0.0;
    z += 0.0;
    std::size_t slot = hash(x, y, z) & (table_.size() - 1);
    while (table_[slot] >= 0) {
      const double* p = &xyz_[3 * static_cast<std::size_t>(table_[slot])];
      if (p[0] == x && p[1] == y && p[2] == z) return table_[slot];
      slot = (slot + 1) & (table_.size() - 1);
    }
    soup_.addVertex(x, y, z);  // checks finiteness (NaN would never match) and the vertex limit
    const int index = static_cast<int>(xyz_.size() / 3);
    xyz_.insert(xyz_.end(), {x, y, z});
    table_[slot] = index;
    if (2 * xyz_.size() / 3 >= table_.size()) grow();
    return index;
  }

 private:
  static std::size_t hash(double x, double y, double z) {
    std::uint64_t h = std::bit_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= std::bit_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= std::bit_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h ^ (h >> 31));
  }

  void grow() {
    std::vector<int>(2 * table_.size(), -1).swap(table_);
    for (std::size_t v = 0; v < xyz_.size() / 3; ++v) {
      std::size_t slot = hash(xyz_[3 * v], xyz_[3 * v + 1], xyz_[3 * v + 2]) & (table_.size() - 1);
      while (table_[slot] >= 0) slot = (slot + 1) & (table_.size() - 1);
      table_[slot] = static_cast<int>(v);
    }
  }

  SoupBuilder& soup_;
  std::vector<int> table_;   // vertex index or -1; size a power of two
  std::vector<double> xyz_;  // the merged vertices
};

// Adds the triangles of a fanned polygon of merged corners, except the collapsed ones.
void addFan(SoupBuilder& soup, const std::vector<int>& corners) {
  for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
    const int a = corners[0], b = corners[k], c = corners[k + 1];
    if (a != b && b != c && a != c) soup.addTriangle(a, b, c);
  }
}

bool sameWord(std::string_view word, std::string_view keyword) {
  if (word.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(word[i])) != keyword[i]) return false;
  return true;
}

float littleEndianFloat(const char* bytes) {
  std::uint32_t bits = 0;
  for (int i = 3; i >= 0; --i) bits = (bits << 8) | static_cast<unsigned char>(bytes[i]);
  return std::bit_cast<float>(bits);
}

PolygonSoup readBinaryStl(Cursor& cursor) {
  cursor.placeByByte();
  SoupBuilder soup(cursor);
  VertexMerger merger(soup);
  cursor.take(80, "the 80-byte header");
  const std::string_view count_bytes = cursor.take(4, "the triangle count");
  std::uint32_t count = 0;
  for (int i = 3; i >= 0; --i) count = (count << 8) | static_cast<unsigned char>(count_bytes[static_cast<std::size_t>(i)]);
  std::vector<int> corners(3);
  for (std::uint32_t t = 0; t < count; ++t) {
    const std::string_view triangle = cursor.take(50, "a triangle (50 bytes)");
    for (int c = 0; c < 3; ++c) {
      const char* p = triangle.data() + 12 + 12 * c;  // after the normal
      corners[static_cast<std::size_t>(c)] =
          merger.index(littleEndianFloat(p), littleEndianFloat(p + 4), littleEndianFloat(p + 8));
    }
    addFan(soup, corners);
  }
  return soup.finish();
}

PolygonSoup readAsciiStl(Cursor& cursor) {
  SoupBuilder soup(cursor);
  VertexMerger merger(soup);
  const std::string number = "a number";
  const auto expect = [&](std::string_view keyword) {
    std::string_view w;
    const bool found = cursor.nextWord(w);
    if (!found || !sameWord(w, keyword))
      cursor.fail(quoted(keyword), found ? quoted(w) : "the end of the file");
  };
  expect("solid");
  cursor.skipRestOfLine();  // the solid's name
  std::vector<int> corners;
  std::string_view w;
  while (cursor.nextWord(w)) {
    if (sameWord(w, "endsolid")) {
      cursor.skipRestOfLine();
      if (!cursor.nextWord(w)) break;
      if (!sameWord(w, "solid")) cursor.fail("\"solid\" or the end of the file after \"endsolid\"", quoted(w));
      cursor.skipRestOfLine();
      continue;
    }
    if (!sameWord(w, "facet")) cursor.fail("\"facet\" or \"endsolid\"", quoted(w));
    expect("normal");
    for (int k = 0; k < 3; ++k) cursor.number(number);  // the normal: recomputed by whoever needs it
    expect("outer");
    expect("loop");
    corners.clear();
    while (true) {
      const std::string_view corner = cursor.word("\"vertex\" or \"endloop\"");
      if (sameWord(corner, "endloop")) break;
      if (!sameWord(corner, "vertex")) cursor.fail("\"vertex\" or \"endloop\"", quoted(corner));
      const double x = cursor.number(number), y = cursor.number(number), z = cursor.number(number);
      corners.push_back(merger.index(x, y, z));
    }
    if (corners.size() < 3) cursor.fail("a facet of at least 3 vertices", std::to_string(corners.size()));
    addFan(soup, corners);
    expect("endfacet");
  }
  return soup.finish();
}

}  // namespace

PolygonSoup readStl(std::string_view bytes, const std::string& name) {
  Cursor cursor(bytes, name);
  // Binary when the size is what the count at byte 80 announces (some binary files start with
  // "solid" too); otherwise ascii if it starts with "solid".
  if (bytes.size() >= 84) {
    std::uint32_t count = 0;
    for (int i = 83; i >= 80; --i) count = (count << 8) | static_cast<unsigned char>(bytes[static_cast<std::size_t>(i)]);
    const std::uint64_t expected = 84 + 50 * static_cast<std::uint64_t>(count);
    if (expected == bytes.size()) return readBinaryStl(cursor);
    std::string_view first;
    if (!(Cursor(bytes, name).nextWord(first) && sameWord(first, "solid")))
      cursor.failAtByte("a binary STL of 84 + 50 × " + std::to_string(count) + " = " + std::to_string(expected) +
                            " bytes (the triangle count at byte 80), or an ascii STL starting with \"solid\"",
                        std::to_string(bytes.size()) + " bytes");
  }
  return readAsciiStl(cursor);
}

}  // namespace filum::geometry::mesh_parsing
