// TriangleMeshSurface: a closed triangle mesh (an organ, a vessel wall) with the two queries
// contacts need, both from CGAL (the only place filum includes CGAL: src/cgal/, behind this
// pimpl, so that no other file pays its compile time):
//   - closest point of the surface to x: CGAL::AABB_tree over the faces (AABB_face_graph_
//     triangle_primitive), closest_point() with accelerated distance queries;
//   - inside test: CGAL::Side_of_triangle_mesh (ray shooting through its own AABB tree, parity
//     of the crossings), exact for a closed, consistently oriented mesh.
// Signed distance d(x) = ±|x − closest(x)|, negative inside. Files are read by filum's reader
// (geometry/mesh_file.hpp: .off, .obj, .stl, .ply; polygons fanned into triangles, STL corners
// merged), not CGAL's, whose OBJ reader refuses common exports.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "filum/core/types.hpp"

namespace filum::collision {

class TriangleMeshSurface {
 public:
  using Triangle = std::array<int, 3>;

  /// vertices: V × 3 (m); triangles: vertex indices. Throws std::invalid_argument if an index is
  /// out of range, the mesh is not a manifold surface (a face CGAL's Surface_mesh refuses) or it
  /// is not closed (the inside test needs a closed mesh).
  TriangleMeshSurface(const Points& vertices, const std::vector<Triangle>& triangles);
  ~TriangleMeshSurface();
  TriangleMeshSurface(const TriangleMeshSurface&) = delete;
  TriangleMeshSurface& operator=(const TriangleMeshSurface&) = delete;

  /// Reads a mesh file (geometry::readMeshFile; format by extension: .off, .obj, .stl, .ply),
  /// scales it by `scale` (metres per unit of the file) and translates it by `translation` (m).
  /// Throws std::runtime_error naming the file and problem.
  static std::unique_ptr<TriangleMeshSurface> read(const std::string& path, double scale = 1.0,
                                                   const Vec3& translation = Vec3::Zero());

  int vertexCount() const;
  int triangleCount() const;
  const Points& vertices() const;
  const std::vector<Triangle>& triangles() const;
  const Eigen::AlignedBox3d& bounds() const;

  /// Closest point of the surface to x (AABB tree).
  Vec3 closestPoint(const Vec3& x) const;
  /// The same, and the outward unit normal of the face it lies on.
  Vec3 closestPoint(const Vec3& x, Vec3& face_normal) const;
  /// x strictly inside the closed surface (points on it count as outside).
  bool inside(const Vec3& x) const;
  /// Outward unit normal of the face nearest to x (for points on the surface, where x − closest
  /// has no direction).
  Vec3 nearestFaceNormal(const Vec3& x) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace filum::collision
