// SphereObstacle: a fixed ball of centre c and radius R. Signed distance d(x) = |x − c| − R,
// normal (x − c)/|x − c|.
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"

namespace filum::collision {

/// The surface sample of a ball (centre c, radius R, moving at velocity v) for point x; the
/// normal at the centre itself is taken as +z.
SurfaceSample sampleBall(const Vec3& center, double radius, const Vec3& velocity, const Vec3& x);

class SphereObstacle final : public Obstacle {
 public:
  SphereObstacle(const Vec3& center, double radius) : center_(center), radius_(radius) {}
  /// "center": [x, y, z] (m), "radius": R (m) > 0, "friction": μ.
  static std::unique_ptr<SphereObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "SphereObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;
  ObstacleShape shape() const override { return ObstacleShape::sphere(center_, radius_); }

 private:
  Vec3 center_;
  double radius_;
};

}  // namespace filum::collision
