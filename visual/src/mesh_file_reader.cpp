#include "filum/visual/mesh_file_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "filum/visual/obj_reader.hpp"
#include "filum/visual/off_reader.hpp"
#include "filum/visual/ply_reader.hpp"

namespace filum::visual {

TriangleMesh readMeshFile(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  TriangleMesh mesh;
  if (extension == ".obj")
    mesh = readObj(path);
  else if (extension == ".off")
    mesh = readOff(path);
  else if (extension == ".ply")
    mesh = readPly(path);
  else
    throw std::runtime_error(path + ": unknown mesh format \"" + extension + "\" (expected .obj, .off or .ply)");
  computeVertexNormals(mesh);
  return mesh;
}

}  // namespace filum::visual
