// Wavefront OBJ (mesh_file.hpp): "v" lines and "f" lines; everything else is ignored, as real
// exports carry groups ("g", "group"), objects, smoothing groups, materials ("mtllib",
// "usemtl"), texture coordinates and normals ("vt", "vn") that a surface for contacts and
// drawing does not need.
#include <vector>

#include "mesh_parsing.hpp"

namespace filum::geometry::mesh_parsing {

namespace {

// The vertex index of a face corner "i", "i/t", "i//n" or "i/t/n", 0-based: i is 1-based, or
// negative for relative to the last vertex read (-1 is the last one).
long long cornerIndex(const Cursor& cursor, std::string_view corner, long long vertex_count) {
  long long index = 0;
  if (!parseInteger(corner.substr(0, corner.find('/')), index) || index == 0)
    cursor.fail("face corners \"i\", \"i/t\", \"i//n\" or \"i/t/n\" with a vertex index i != 0", quoted(corner));
  if (index > vertex_count || index < -vertex_count)
    cursor.fail("vertex indices in [1, " + std::to_string(vertex_count) + "] or [-" + std::to_string(vertex_count) +
                    ", -1] (the vertices so far)",
                std::to_string(index));
  return index > 0 ? index - 1 : vertex_count + index;
}

}  // namespace

PolygonSoup readObj(std::string_view bytes, const std::string& name) {
  Cursor cursor(bytes, name);
  SoupBuilder soup(cursor);
  std::vector<long long> polygon;
  const std::string vertex_line = "\"v x y z\" with numbers";  // built once, not per vertex
  std::string_view line;
  while (cursor.nextLine(line)) {
    Cursor words(line, name, true, cursor.line());
    std::string_view tag;
    if (!words.nextWord(tag)) continue;
    if (tag == "v") {
      const double x = words.number(vertex_line), y = words.number(vertex_line), z = words.number(vertex_line);
      // Extra numbers (w, or the vertex colour r g b of some exporters) are ignored.
      soup.addVertex(x, y, z);
    } else if (tag == "f") {
      polygon.clear();
      std::string_view corner;
      while (words.nextWord(corner)) polygon.push_back(cornerIndex(cursor, corner, soup.vertexCount()));
      soup.addPolygon(polygon);
    }
  }
  return soup.finish();
}

}  // namespace filum::geometry::mesh_parsing
