#include "filum/visual/triangle_mesh.hpp"

#include <utility>

#include <Eigen/Geometry>

namespace filum::visual {

void computeVertexNormals(TriangleMesh& mesh) {
  // n_v = Σ_f (b − a) × (c − a) over the triangles f = (a, b, c) around v: the cross product
  // is twice the area times the unit face normal, so large faces weigh more.
  mesh.normals.setZero(mesh.vertices.rows(), 3);
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Vec3 a = mesh.vertices.row(mesh.triangles(f, 0)).transpose();
    const Vec3 b = mesh.vertices.row(mesh.triangles(f, 1)).transpose();
    const Vec3 c = mesh.vertices.row(mesh.triangles(f, 2)).transpose();
    const Vec3 n = (b - a).cross(c - a);
    for (int k = 0; k < 3; ++k) mesh.normals.row(mesh.triangles(f, k)) += n.transpose();
  }
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const double norm = mesh.normals.row(v).norm();
    if (norm > 0.0)
      mesh.normals.row(v) /= norm;
    else
      mesh.normals.row(v) = Vec3::UnitZ().transpose();
  }
}

TriangleMesh triangleMesh(geometry::PolygonSoup soup) {
  TriangleMesh mesh;
  mesh.vertices = std::move(soup.vertices);
  mesh.triangles = std::move(soup.triangles);
  computeVertexNormals(mesh);
  return mesh;
}

void meshBounds(const TriangleMesh& mesh, Vec3& lower, Vec3& upper) {
  lower = mesh.vertices.colwise().minCoeff().transpose();
  upper = mesh.vertices.colwise().maxCoeff().transpose();
}

}  // namespace filum::visual
