// Reads a triangle mesh from a file by its extension: .obj (obj_reader.hpp), .off
// (off_reader.hpp), .ply (ply_reader.hpp); smooth vertex normals are computed from the faces.
#pragma once

#include <string>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// Throws std::runtime_error naming the file for an unknown extension, a missing file or a
/// malformed one.
TriangleMesh readMeshFile(const std::string& path);

}  // namespace filum::visual
