// TriangleMeshObstacle: a triangle mesh (a closed organ; as a cavity also a vessel open at its
// ends) read from an OFF/OBJ/STL/PLY
// file (TriangleMeshSurface: filum's reader, CGAL's queries). Signed distance to the surface d(x) = ±|x − c(x)| with c the
// closest point (AABB tree) and the sign from the inside test; outward normal
// (x − c)/|x − c| outside, (c − x)/|c − x| inside, the nearest face's normal on the surface.
// With "side": "inside" the mesh is a cavity (an abdomen, a lumen closed at its ends): bodies stay
// inside it, the obstacle is everything outside, d_cavity = −d and the normal points into the
// cavity. Which side x is on comes from the nearest face's normal, (x − c)·n_f, when x lies
// clearly off the face's plane (|(x − c)·n_f| > ½|x − c|: away from edges where faces meet at an
// angle, that sign is the inside test's), and from the exact inside test otherwise — a cavity
// asks about every sphere in it, far from the wall too, and the ray-shooting test costs more than
// the closest-point query.
// A cavity's mesh may be open (a vessel segmented from a scan, open at its inlet and outlets: a
// lumen): which side x is on then comes from the angle-weighted pseudo-normal of the closest
// feature (triangle_mesh_surface.hpp), the rim of an opening is a thin edge pushing away on both
// sides, and a body farther outside the wall than the contact distance is free (an instrument on
// its way to the introducer). The
// inner side is found from the faces' winding: the volume enclosed with the holes closed is
// positive for faces wound counter-clockwise seen from outside the lumen; a mesh wound the other
// way is turned round, one that encloses no volume is refused.
// Built only with FILUM_WITH_CGAL (a scene naming it otherwise gets an error saying so).
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"
#include "filum/collision/triangle_mesh_surface.hpp"

namespace filum::collision {

class TriangleMeshObstacle final : public Obstacle {
 public:
  explicit TriangleMeshObstacle(std::shared_ptr<const TriangleMeshSurface> surface, bool cavity = false);
  /// "file": mesh file, relative to the scene file's folder (or absolute); "units": "m"
  /// (default), "cm" or "mm", the unit of the file's coordinates; "scale": s > 0 (default 1),
  /// multiplied with the units (geometry/mesh_units.hpp); "translation": [x, y, z] (m, default
  /// 0); "friction": μ; "side": "outside" (default: a solid organ the bodies stay out of; the
  /// mesh must be closed) or "inside" (a cavity or lumen they stay in; closed or open). Errors name the scene-file place and what the reader or
  /// CGAL found wrong.
  static std::unique_ptr<TriangleMeshObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "TriangleMeshObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;

  ObstacleShape shape() const override { return ObstacleShape::triangleMesh(*surface_, cavity_); }

  const TriangleMeshSurface& surface() const { return *surface_; }
  /// The bodies stay inside the mesh ("side": "inside").
  bool cavity() const { return cavity_; }

 private:
  bool sampleCavity(const Vec3& x, double max_distance, SurfaceSample& out) const;
  /// A cavity whose mesh is open (a segmented vessel): sides from pseudo-normals.
  bool sampleLumen(const Vec3& x, double max_distance, SurfaceSample& out) const;

  std::shared_ptr<const TriangleMeshSurface> surface_;
  bool cavity_ = false;
};

}  // namespace filum::collision
