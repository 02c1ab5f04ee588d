#include "filum/collision/sphere_obstacle.hpp"

namespace filum::collision {

SurfaceSample sampleBall(const Vec3& center, double radius, const Vec3& velocity, const Vec3& x) {
  // d(x) = |x − c| − R, n = (x − c)/|x − c|
  SurfaceSample out;
  const Vec3 r = x - center;
  const double norm = r.norm();
  out.normal = norm > 0.0 ? Vec3(r / norm) : Vec3::UnitZ();
  out.distance = norm - radius;
  out.point = center + radius * out.normal;
  out.velocity = velocity;
  return out;
}

std::unique_ptr<SphereObstacle> SphereObstacle::fromParams(const Params& p) {
  auto sphere = std::make_unique<SphereObstacle>(p.vec3({"center", "m"}), p.positive({"radius", "m"}));
  sphere->readCommon(p);
  return sphere;
}

bool SphereObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  if ((x - center_).norm() - radius_ > max_distance) return false;
  out = sampleBall(center_, radius_, Vec3::Zero(), x);
  return true;
}

}  // namespace filum::collision
