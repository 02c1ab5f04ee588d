#include "filum/geometry/mesh_file.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "filum/core/input_file.hpp"
#include "mesh_parsing.hpp"

namespace filum::geometry {

PolygonSoup readMesh(std::string_view bytes, MeshFormat format, const std::string& name) {
  if (bytes.size() > kMaxMeshFileBytes)
    throw std::runtime_error(name + ": expected a mesh of at most " + byteSize(kMaxMeshFileBytes) + ", found " +
                             byteSize(bytes.size()));
  switch (format) {
    case MeshFormat::kObj: return mesh_parsing::readObj(bytes, name);
    case MeshFormat::kOff: return mesh_parsing::readOff(bytes, name);
    case MeshFormat::kPly: return mesh_parsing::readPly(bytes, name);
    case MeshFormat::kStl: return mesh_parsing::readStl(bytes, name);
    case MeshFormat::kVtp: return mesh_parsing::readVtp(bytes, name);
  }
  throw std::runtime_error(name + ": expected a mesh format (OBJ, OFF, PLY, STL, VTP), found none");
}

MeshFormat meshFormatOfPath(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension == ".obj") return MeshFormat::kObj;
  if (extension == ".off") return MeshFormat::kOff;
  if (extension == ".ply") return MeshFormat::kPly;
  if (extension == ".stl") return MeshFormat::kStl;
  if (extension == ".vtp") return MeshFormat::kVtp;
  throw std::runtime_error(path + ": expected a mesh file .obj, .off, .ply, .stl or .vtp, found the extension \"" + extension +
                           "\"");
}

PolygonSoup readMeshFile(const std::string& path) {
  const MeshFormat format = meshFormatOfPath(path);
  // Before a byte is read: a FIFO or a device would block or never end, a huge file would fill
  // the memory (input_file.hpp).
  if (const std::string problem = inputFileProblem(path, kMaxMeshFileBytes); !problem.empty())
    throw std::runtime_error(path + ": expected a regular mesh file of at most " + byteSize(kMaxMeshFileBytes) +
                             ", found " + problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": expected a readable mesh file, found one that cannot be opened");
  // At most the limit, even if the file grew since it was checked.
  std::string bytes(static_cast<std::size_t>(std::min(inputFileSize(path), kMaxMeshFileBytes)), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return readMesh(bytes, format, path);
}

}  // namespace filum::geometry
