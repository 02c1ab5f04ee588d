// Stanford PLY export of one triangle mesh (Blender, MeshLab): ASCII, float x y z nx ny nz per
// vertex and "3 a b c" faces; 9 significant digits. Nothing non-finite is written.
#pragma once

#include <string>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// Throws std::runtime_error if the file cannot be written or a value is not finite.
void writePly(const std::string& path, const TriangleMesh& mesh);

}  // namespace filum::visual
