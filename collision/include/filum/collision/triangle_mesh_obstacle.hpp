// TriangleMeshObstacle: a closed triangle mesh (an organ, a vessel) read from an OFF/OBJ/STL/PLY
// file (TriangleMeshSurface: filum's reader, CGAL's queries). Signed distance to the surface d(x) = ±|x − c(x)| with c the
// closest point (AABB tree) and the sign from the inside test; outward normal
// (x − c)/|x − c| outside, (c − x)/|c − x| inside, the nearest face's normal on the surface.
// Built only with FILUM_WITH_CGAL (a scene naming it otherwise gets an error saying so).
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"
#include "filum/collision/triangle_mesh_surface.hpp"

namespace filum::collision {

class TriangleMeshObstacle final : public Obstacle {
 public:
  explicit TriangleMeshObstacle(std::shared_ptr<const TriangleMeshSurface> surface);
  /// "file": mesh file, relative to the scene file's folder (or absolute); "units": "m"
  /// (default), "cm" or "mm", the unit of the file's coordinates; "scale": s > 0 (default 1),
  /// multiplied with the units (geometry/mesh_units.hpp); "translation": [x, y, z] (m, default
  /// 0); "friction": μ. Errors name the scene-file place and what the reader or CGAL found wrong.
  static std::unique_ptr<TriangleMeshObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "TriangleMeshObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;

  const TriangleMeshSurface& surface() const { return *surface_; }

 private:
  std::shared_ptr<const TriangleMeshSurface> surface_;
};

}  // namespace filum::collision
