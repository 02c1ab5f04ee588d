// Wavefront OBJ export of triangle meshes (Blender, MeshLab, ParaView): "v" vertices, "vn"
// normals and "f i//i" faces (1-based), several meshes as named objects ("o name") in one file.
// 9 significant digits (float precision, what the importers keep). Nothing non-finite is written.
#pragma once

#include <string>
#include <vector>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

struct NamedMesh {
  std::string name;          // object name (e.g. the node path and the model name)
  const TriangleMesh* mesh;  // not owned
};

/// Throws std::runtime_error if the file cannot be written or a value is not finite.
void writeObj(const std::string& path, const std::vector<NamedMesh>& meshes);

}  // namespace filum::visual
