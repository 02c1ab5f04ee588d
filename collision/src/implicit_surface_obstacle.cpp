#include "filum/collision/implicit_surface_obstacle.hpp"

#include <cmath>

namespace filum::collision {

ImplicitSurfaceObstacle::ImplicitSurfaceObstacle(const Points& skeleton, double radius, double sharpness)
    : surface_(radius, sharpness) {
  surface_.addPolyline(skeleton);
  for (int k = 0; k < skeleton.rows(); ++k) skeleton_box_.extend(skeleton.row(k).transpose());
}

std::unique_ptr<ImplicitSurfaceObstacle> ImplicitSurfaceObstacle::fromParams(const Params& p) {
  const Points skeleton = p.points({"skeleton", "m"}, 2);
  const double radius = p.positive({"radius", "m"});
  const double sharpness = p.nonNegative({"sharpness", "1/m"}, 0.0);
  auto obstacle = std::make_unique<ImplicitSurfaceObstacle>(skeleton, radius, sharpness);
  obstacle->readCommon(p);
  return obstacle;
}

bool ImplicitSurfaceObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // Early out: the surface stays within a few radii of its skeleton (the Cauchy kernel blends
  // neighbouring parts, so allow 3 R), so farther points cannot be in contact.
  if (skeleton_box_.exteriorDistance(x) > 3.0 * surface_.radius() + max_distance) return false;
  // f = T − F, ∇f = −∇F, d ≈ f / |∇f|
  const geometry::SegmentField field = surface_.fieldAndGradient(x);
  const double f = surface_.isoValue() - field.value;
  const double g = field.gradient.norm();
  // A flat field: far outside (no contact), or a critical point deep inside (no direction to push).
  if (!(g > 0.0)) return false;
  const double d = f / g;
  if (d > max_distance) return false;
  out.distance = d;
  out.normal = -field.gradient / g;
  out.point = x - d * out.normal;
  out.velocity.setZero();
  return true;
}

}  // namespace filum::collision
