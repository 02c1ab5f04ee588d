#include "filum/collision/probe_sphere.hpp"

#include "filum/collision/sphere_obstacle.hpp"

namespace filum::collision {

ProbeSphere::ProbeSphere(double radius, geometry::ScriptedPath path) : radius_(radius), path_(std::move(path)) {
  moveTo(0.0);
}

std::unique_ptr<ProbeSphere> ProbeSphere::fromParams(const Params& p) {
  const double radius = p.positive({"radius", "m"});
  auto probe = std::make_unique<ProbeSphere>(radius, geometry::ScriptedPath::fromParams(p, "path"));
  probe->readCommon(p);
  return probe;
}

void ProbeSphere::moveTo(double t) {
  center_ = path_.position(t);
  velocity_ = path_.velocity(t);
}

bool ProbeSphere::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  if ((x - center_).norm() - radius_ > max_distance) return false;
  out = sampleBall(center_, radius_, velocity_, x);
  return true;
}

}  // namespace filum::collision
