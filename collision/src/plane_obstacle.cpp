#include "filum/collision/plane_obstacle.hpp"

#include <stdexcept>

namespace filum::collision {

PlaneObstacle::PlaneObstacle(const Vec3& point, const Vec3& normal) : point_(point), normal_(normal.normalized()) {
  if (!(normal.norm() > 0.0)) throw std::invalid_argument("PlaneObstacle: the normal must not be zero");
}

std::unique_ptr<PlaneObstacle> PlaneObstacle::fromParams(const Params& p) {
  const Vec3 point = p.vec3({"point", "m"}, Vec3::Zero());
  const Vec3 normal = p.vec3({"normal", "1"}, Vec3::UnitZ());
  if (!(normal.norm() > 0.0)) p.fail("normal", "a non-zero normal [x, y, z]");
  auto plane = std::make_unique<PlaneObstacle>(point, normal);
  plane->readCommon(p);
  return plane;
}

bool PlaneObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // d(x) = n·(x − point)
  const double d = normal_.dot(x - point_);
  if (d > max_distance) return false;
  out.distance = d;
  out.point = x - d * normal_;
  out.normal = normal_;
  out.velocity.setZero();
  return true;
}

}  // namespace filum::collision
