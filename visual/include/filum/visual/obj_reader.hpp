// Wavefront OBJ meshes (organs, vessels exported from Blender, MeshLab, ...): "v x y z" vertices
// and "f" faces (indices 1-based or negative, "i", "i/t", "i//n", "i/t/n" forms); polygons are
// fanned into triangles; normals, texture coordinates, groups and materials are ignored (the
// normals are recomputed from the triangles, smooth).
#pragma once

#include <string>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// Throws std::runtime_error "file:line: what" on a malformed file or an index out of range.
TriangleMesh readObj(const std::string& path);

}  // namespace filum::visual
