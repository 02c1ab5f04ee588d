#include "filum/visual/mesh_file_reader.hpp"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "filum/core/input_file.hpp"
#include "filum/visual/obj_reader.hpp"
#include "filum/visual/off_reader.hpp"
#include "filum/visual/ply_reader.hpp"

namespace filum::visual {

TriangleMesh readMeshFile(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  // Before a byte is read: a FIFO or a device would block or never end; a header announcing
  // more vertices than the file can hold would allocate them (input_file.hpp).
  if (const std::string problem = inputFileProblem(path, kMaxMeshFileBytes); !problem.empty())
    throw std::runtime_error(path + ": expected a regular mesh file of at most " + byteSize(kMaxMeshFileBytes) +
                             ", found " + problem);
  if (const std::string problem = meshHeaderProblem(path); !problem.empty())
    throw std::runtime_error(path + ": " + problem);
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
