// Stanford PLY meshes (.ply; scanners, MeshLab, Blender), ASCII, binary little- and big-endian:
// the "vertex" element's x, y, z (any numeric type) and the "face" element's vertex index list
// ("vertex_indices" or "vertex_index"); other properties and elements are skipped. Polygons are
// fanned into triangles.
#pragma once

#include <string>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// Throws std::runtime_error "file: what" on a malformed file or an index out of range.
TriangleMesh readPly(const std::string& path);

}  // namespace filum::visual
