// TriangleMeshSurface: a triangle mesh (an organ, a vessel wall) with the queries contacts need,
// from CGAL (the only place filum includes CGAL: src/cgal/, behind this pimpl, so that no other
// file pays its compile time):
//   - closest point of the surface to x: CGAL::AABB_tree over the faces (AABB_face_graph_
//     triangle_primitive), closest_point() with accelerated distance queries;
//   - inside test of a closed mesh: CGAL::Side_of_triangle_mesh (ray shooting through its own
//     AABB tree, parity of the crossings), exact for a closed, consistently oriented mesh;
//   - the side of x near the surface, closed or open: the sign of (x − c)·n with n the
//     angle-weighted pseudo-normal of the feature (face, edge or vertex) c lies on — exact for a
//     closed mesh (J. A. Bærentzen, H. Aanæs, "Signed distance computation using the angle weighted
//     pseudonormal", IEEE TVCG 11 (2005) 243), and what an open mesh (a vessel segmented from a
//     scan, open at its inlet and outlets) has instead of an inside test.
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
  /// out of range, the mesh is not a manifold surface (a face CGAL's Surface_mesh refuses:
  /// non-manifold or inconsistently oriented) or, unless allow_open, it is not closed (the inside
  /// test needs a closed mesh).
  TriangleMeshSurface(const Points& vertices, const std::vector<Triangle>& triangles, bool allow_open = false);
  ~TriangleMeshSurface();
  TriangleMeshSurface(const TriangleMeshSurface&) = delete;
  TriangleMeshSurface& operator=(const TriangleMeshSurface&) = delete;

  /// Reads a mesh file (geometry::readMeshFile; format by extension: .off, .obj, .stl, .ply),
  /// scales it by `scale` (metres per unit of the file) and translates it by `translation` (m).
  /// Throws std::runtime_error naming the file and problem.
  static std::unique_ptr<TriangleMeshSurface> read(const std::string& path, double scale = 1.0,
                                                   const Vec3& translation = Vec3::Zero(), bool allow_open = false);
  /// The same surface with every face wound the other way (its normals reversed).
  std::unique_ptr<TriangleMeshSurface> reversed() const;

  /// No border edges.
  bool closed() const;
  /// The signed volume Σ_f a·(b × c)/6 the faces enclose, each hole (a cycle of border edges)
  /// closed by a fan of triangles from its border's centroid: > 0 when the faces are wound
  /// counter-clockwise seen from outside (normals outwards), < 0 when wound inwards. `scale`
  /// (out) is Σ |a·(b × c)|/6 over the same triangles, the size of its round-off / ε.
  double enclosedVolume(double& scale) const;

  int vertexCount() const;
  int triangleCount() const;
  const Points& vertices() const;
  const std::vector<Triangle>& triangles() const;
  const Eigen::AlignedBox3d& bounds() const;

  /// Closest point of the surface to x (AABB tree).
  Vec3 closestPoint(const Vec3& x) const;
  /// The same, and the outward unit normal of the face it lies on.
  Vec3 closestPoint(const Vec3& x, Vec3& face_normal) const;
  /// x strictly inside the closed surface (points on it count as outside). Throws
  /// std::logic_error on an open mesh (use closestFeature's pseudo-normal).
  bool inside(const Vec3& x) const;

  /// The closest point c of the surface to x, the angle-weighted pseudo-normal of the face, edge
  /// or vertex c lies on (unit, outwards for counter-clockwise faces), and whether that edge or
  /// vertex lies on a border of an open mesh.
  struct ClosestFeature {
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
    bool on_border = false;
  };
  ClosestFeature closestFeature(const Vec3& x) const;
  /// Outward unit normal of the face nearest to x (for points on the surface, where x − closest
  /// has no direction).
  Vec3 nearestFaceNormal(const Vec3& x) const;

 private:
  void computePseudoNormals();

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace filum::collision
