#include "filum/collision/capsule_obstacle.hpp"

#include "filum/collision/segment_closest_points.hpp"
#include "filum/collision/sphere_obstacle.hpp"

namespace filum::collision {

std::unique_ptr<CapsuleObstacle> CapsuleObstacle::fromParams(const Params& p) {
  auto capsule = std::make_unique<CapsuleObstacle>(p.vec3({"a", "m"}), p.vec3({"b", "m"}), p.positive({"radius", "m"}));
  capsule->readCommon(p);
  return capsule;
}

bool CapsuleObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // The ball of radius R around the closest point of the axis.
  const double t = closestParameterOnSegment(a_, b_, x);
  const Vec3 c = a_ + t * (b_ - a_);
  if ((x - c).norm() - radius_ > max_distance) return false;
  out = sampleBall(c, radius_, Vec3::Zero(), x);
  return true;
}

}  // namespace filum::collision
