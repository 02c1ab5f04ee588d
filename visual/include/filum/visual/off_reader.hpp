// Object File Format (.off, Geomview; CGAL and many mesh datasets): "OFF", counts
// "V F E", V lines "x y z", F lines "n i_1 ... i_n" (0-based). Polygons are fanned into
// triangles; "#" starts a comment; per-vertex or per-face colours are ignored.
#pragma once

#include <string>

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// Throws std::runtime_error "file: what" on a malformed file or an index out of range.
TriangleMesh readOff(const std::string& path);

}  // namespace filum::visual
