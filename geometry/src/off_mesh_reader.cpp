// Object File Format (mesh_file.hpp; Geomview, CGAL, many mesh datasets): "OFF" (or COFF, NOFF,
// CNOFF, STOFF...: colours, normals and texture coordinates after the coordinates, ignored), the
// counts "V F [E]", V lines "x y z ...", F lines "n i_1 ... i_n [colour]" with 0-based indices;
// "#" starts a comment.
#include <vector>

#include "mesh_parsing.hpp"

namespace filum::geometry::mesh_parsing {

PolygonSoup readOff(std::string_view bytes, const std::string& name) {
  Cursor cursor(bytes, name);
  SoupBuilder soup(cursor);
  constexpr char kComment = '#';
  const std::string_view header = cursor.word("\"OFF\"", kComment);
  if (header.size() < 3 || header.substr(header.size() - 3) != "OFF" || header.find('4') != std::string_view::npos ||
      header.find('n') != std::string_view::npos)
    cursor.fail("\"OFF\" (or COFF, NOFF, CNOFF, STOFF: a 3D ascii OFF file)", quoted(header));
  const long long vertex_count = cursor.integer("the vertex count V of \"V F E\"", kComment);
  const long long face_count = cursor.integer("the face count F of \"V F E\"", kComment);
  cursor.skipRestOfLine();  // the edge count E, unused
  // Before allocating: a vertex takes at least 6 bytes ("x y z\n"), a face 8 ("3 a b c\n").
  const auto bytes_after = static_cast<long double>(cursor.remaining());
  if (vertex_count < 0 || face_count < 0 || vertex_count * 6.0L > bytes_after || face_count * 8.0L > bytes_after)
    cursor.fail("counts \"V F E\" that fit in the file (a vertex takes at least 6 bytes, a face 8)",
                "a header announcing " + std::to_string(vertex_count) + " vertices and " + std::to_string(face_count) +
                    " faces in a file of " + std::to_string(cursor.size()) + " bytes");
  soup.expectVertices(vertex_count);
  // The place is the line: messages built once, not per vertex.
  const std::string what = "a vertex line \"x y z\" of numbers", face = "a face line \"n i_1 ... i_n\" of integers";
  for (long long i = 0; i < vertex_count; ++i) {
    const double x = cursor.number(what, kComment), y = cursor.number(what, kComment), z = cursor.number(what, kComment);
    soup.addVertex(x, y, z);
    cursor.skipRestOfLine();  // normal, colour, texture coordinates
  }
  std::vector<long long> polygon;
  for (long long f = 0; f < face_count; ++f) {
    const long long n = cursor.integer(face, kComment);
    // Before reading n indices: each takes at least 2 bytes.
    if (n < 3 || n > static_cast<long long>(cursor.remaining() / 2))
      cursor.fail("a face of at least 3 vertices whose indices fit in the rest of the file",
                  "a face announcing " + std::to_string(n) + " vertices");
    polygon.clear();
    for (long long k = 0; k < n; ++k)
      polygon.push_back(cursor.integer(face, kComment));
    soup.addPolygon(polygon);
    cursor.skipRestOfLine();  // face colour
  }
  return soup.finish();
}

}  // namespace filum::geometry::mesh_parsing
