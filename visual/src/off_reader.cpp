#include "filum/visual/off_reader.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace filum::visual {

TriangleMesh readOff(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the mesh file");
  // The whole file as whitespace-separated words, comments removed.
  std::stringstream words;
  std::string line;
  while (std::getline(in, line)) words << line.substr(0, line.find('#')) << '\n';
  std::string header;
  words >> header;
  if (header.size() < 3 || header.substr(header.size() - 3) != "OFF")
    throw std::runtime_error(path + ": not an OFF file (first word \"" + header + "\", expected OFF)");
  long vertex_count = -1, face_count = -1, edge_count = 0;
  if (!(words >> vertex_count >> face_count >> edge_count) || vertex_count < 0 || face_count < 1)
    throw std::runtime_error(path + ": expected the counts \"V F E\" after OFF");
  TriangleMesh mesh;
  mesh.vertices.resize(vertex_count, 3);
  for (long i = 0; i < vertex_count; ++i) {
    Vec3 v;
    if (!(words >> v.x() >> v.y() >> v.z()) || !v.allFinite())
      throw std::runtime_error(path + ": vertex " + std::to_string(i) + ": expected three finite numbers");
    std::getline(words, line);  // optional normal or colour (NOFF, COFF)
    mesh.vertices.row(i) = v.transpose();
  }
  std::vector<Eigen::Vector3i> triangles;
  for (long f = 0; f < face_count; ++f) {
    int n = 0;
    if (!(words >> n) || n < 3 || n > vertex_count)
      throw std::runtime_error(path + ": face " + std::to_string(f) + ": expected a vertex count in [3, " +
                               std::to_string(vertex_count) + "] (the vertices of the file)");
    std::vector<int> polygon(n);
    for (int k = 0; k < n; ++k)
      if (!(words >> polygon[k]) || polygon[k] < 0 || polygon[k] >= vertex_count)
        throw std::runtime_error(path + ": face " + std::to_string(f) + ": vertex index out of range [0, " +
                                 std::to_string(vertex_count) + ")");
    std::getline(words, line);  // optional face colour
    for (int k = 1; k + 1 < n; ++k) triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
  }
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) mesh.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  mesh.normals.setZero(mesh.vertices.rows(), 3);
  return mesh;
}

}  // namespace filum::visual
