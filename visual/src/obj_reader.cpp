#include "filum/visual/obj_reader.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace filum::visual {

TriangleMesh readObj(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the mesh file");
  std::vector<Vec3> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::string line;
  int number = 0;
  const auto fail = [&](const std::string& what) {
    throw std::runtime_error(path + ":" + std::to_string(number) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++number;
    std::istringstream words(line);
    std::string tag;
    if (!(words >> tag) || tag[0] == '#') continue;
    if (tag == "v") {
      Vec3 v;
      if (!(words >> v.x() >> v.y() >> v.z()) || !v.allFinite()) fail("expected \"v x y z\" with finite numbers");
      vertices.push_back(v);
    } else if (tag == "f") {
      std::vector<int> polygon;
      std::string token;
      while (words >> token) {
        // "i", "i/t", "i//n", "i/t/n": the vertex index is before the first slash.
        int index = 0;
        try {
          index = std::stoi(token.substr(0, token.find('/')));
        } catch (const std::exception&) {
          fail("bad face vertex \"" + token + "\"");
        }
        const int count = static_cast<int>(vertices.size());
        const int resolved = index > 0 ? index - 1 : count + index;  // negative: relative to the end
        if (index == 0 || resolved < 0 || resolved >= count)
          fail("face vertex " + std::to_string(index) + " out of range (" + std::to_string(count) + " vertices so far)");
        polygon.push_back(resolved);
      }
      if (polygon.size() < 3) fail("a face needs at least 3 vertices");
      for (std::size_t k = 1; k + 1 < polygon.size(); ++k) triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
    }
  }
  TriangleMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i) mesh.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose();
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) mesh.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  if (mesh.triangles.rows() == 0) throw std::runtime_error(path + ": no faces");
  mesh.normals.setZero(mesh.vertices.rows(), 3);
  return mesh;
}

}  // namespace filum::visual
