// CapsuleObstacle: the points within R of the segment [a, b] — an instrument shaft, a vessel
// segment, a rod. Closest point of the axis c = a + t (b − a), t = clamp((x − a)·(b − a)/|b − a|²),
// signed distance |x − c| − R, normal (x − c)/|x − c|.
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"

namespace filum::collision {

class CapsuleObstacle final : public Obstacle {
 public:
  CapsuleObstacle(const Vec3& a, const Vec3& b, double radius) : a_(a), b_(b), radius_(radius) {}
  /// "a", "b": axis endpoints [x, y, z] (m), "radius": R (m) > 0, "friction": μ.
  static std::unique_ptr<CapsuleObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "CapsuleObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;
  ObstacleShape shape() const override { return ObstacleShape::capsule(a_, b_, radius_); }

 private:
  Vec3 a_, b_;
  double radius_;
};

}  // namespace filum::collision
