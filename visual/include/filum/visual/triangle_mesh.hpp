// TriangleMesh: the geometry every visual model hands to the exporters and renderers — vertices,
// one normal per vertex (smooth shading) and triangles as vertex index triples, counter-clockwise
// seen from outside (the right-hand rule gives the outward normal).
#pragma once

#include <Eigen/Core>

#include "filum/core/types.hpp"
#include "filum/geometry/mesh_file.hpp"

namespace filum::visual {

/// F triangles, one per row: indices into the vertices, counter-clockwise seen from outside.
using Triangles = geometry::TriangleIndices;

struct TriangleMesh {
  Points vertices;      // V × 3 (m)
  Points normals;       // V × 3, unit, outward
  Triangles triangles;  // F × 3

  int vertexCount() const { return static_cast<int>(vertices.rows()); }
  int triangleCount() const { return static_cast<int>(triangles.rows()); }
  bool empty() const { return triangles.rows() == 0; }
};

/// Area-weighted vertex normals of the triangles (unit; a vertex of no triangle gets +z).
void computeVertexNormals(TriangleMesh& mesh);

/// A mesh read from a file (geometry::readMeshFile: OBJ, OFF, PLY, STL, VTP) with its smooth vertex
/// normals: triangleMesh(geometry::readMeshFile(path)).
TriangleMesh triangleMesh(geometry::PolygonSoup soup);

/// Axis-aligned bounds of the vertices: lower and upper corners. Precondition: V > 0.
void meshBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper);

}  // namespace filum::visual
