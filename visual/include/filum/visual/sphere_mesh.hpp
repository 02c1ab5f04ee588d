// A UV sphere: `rings` latitude bands between two poles, 2 · rings vertices around; a closed,
// outward-oriented 2-manifold whose vertices lie exactly on the sphere, with exact normals.
#pragma once

#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// The unit sphere centred at the origin; rings >= 2. (rings − 1) · 2 rings + 2 vertices.
TriangleMesh unitSphere(int rings);

/// Appends the sphere (centre, radius) built from `unit` to `out` (vertices, normals, triangles).
void appendSphere(const TriangleMesh& unit, const Vec3& center, double radius, TriangleMesh& out);

/// Replaces `out` by one sphere of `radius` at each row of `centers` (k × 3), sized once: k
/// appends would reallocate the growing mesh k times (quadratic in k).
void sphereSet(const TriangleMesh& unit, const Points& centers, double radius, TriangleMesh& out);
/// The same with sphere i of radius radii[i] (one radius per row of `centers`; else
/// std::invalid_argument).
void sphereSet(const TriangleMesh& unit, const Points& centers, const VecX& radii, TriangleMesh& out);

}  // namespace filum::visual
