// PlaneObstacle: the half-space below a plane through `point` with outward unit normal n — a
// table, an inclined board. Signed distance d(x) = n·(x − point), closest point x − d n.
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"

namespace filum::collision {

class PlaneObstacle final : public Obstacle {
 public:
  /// normal: any non-zero vector (normalized here).
  PlaneObstacle(const Vec3& point, const Vec3& normal);
  /// "point": [x, y, z] (m, default origin), "normal": [x, y, z] (default +z), "friction": μ.
  static std::unique_ptr<PlaneObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "PlaneObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;

  ObstacleShape shape() const override { return ObstacleShape::plane(point_, normal_); }

  const Vec3& point() const { return point_; }
  const Vec3& normal() const { return normal_; }

 private:
  Vec3 point_, normal_;
};

}  // namespace filum::collision
