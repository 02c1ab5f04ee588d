#include "filum/haptics/instrument_capsule.hpp"

#include <algorithm>

#include "filum/collision/segment_closest_points.hpp"
#include "filum/collision/sphere_obstacle.hpp"

namespace filum::haptics {

void InstrumentCapsule::setMotion(const Capsule& start, const Capsule& end, double t0, double h) {
  start_ = start;
  end_ = end;
  t0_ = t0;
  h_ = h;
  velocity_a_ = (end.a - start.a) / h;
  velocity_b_ = (end.b - start.b) / h;
  moveTo(t0);
}

void InstrumentCapsule::moveTo(double t) {
  const double u = std::clamp((t - t0_) / h_, 0.0, 1.0);
  now_.a = start_.a + u * (end_.a - start_.a);
  now_.b = start_.b + u * (end_.b - start_.b);
  now_.radius = start_.radius;
}

bool InstrumentCapsule::sample(const Vec3& x, double max_distance, collision::SurfaceSample& out) const {
  if (!enabled_) return false;
  // The ball of radius R around the closest point c = a + τ (b − a) of the axis, moving with
  // the velocity of that point of the rigid part, v_a + τ (v_b − v_a).
  const double tau = collision::closestParameterOnSegment(now_.a, now_.b, x);
  const Vec3 c = now_.a + tau * (now_.b - now_.a);
  if ((x - c).norm() - now_.radius > max_distance) return false;
  out = collision::sampleBall(c, now_.radius, velocity_a_ + tau * (velocity_b_ - velocity_a_), x);
  return true;
}

}  // namespace filum::haptics
