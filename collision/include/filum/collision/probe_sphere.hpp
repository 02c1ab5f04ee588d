// ProbeSphere: the virtual probe of paper Fig. 1a ("the user manipulates a virtual probe
// represented by the red sphere, via the Phantom"): a ball of radius R whose centre follows a
// scripted trajectory (geometry::ScriptedPath keyframes) and pushes threads through contacts.
// A haptic device will drive the same component later (the haptics library sets the centre);
// the force the threads exert on the probe is what the device renders (ContactPipeline::
// obstacleForce).
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"
#include "filum/geometry/scripted_path.hpp"

namespace filum::collision {

class ProbeSphere final : public Obstacle {
 public:
  ProbeSphere(double radius, geometry::ScriptedPath path);
  /// "radius": R (m) > 0, "path": [{"time": t, "position": [x, y, z]}, ...] with
  /// "interpolation": "linear" (default) or "smooth", "friction": μ.
  static std::unique_ptr<ProbeSphere> fromParams(const Params& p);

  std::string typeName() const override { return "ProbeSphere"; }
  void moveTo(double t) override;
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;
  double speed() const override { return velocity_.norm(); }
  ObstacleShape shape() const override { return ObstacleShape::sphere(center_, radius_); }
  ObstacleShape shapeAt(double t) const override { return ObstacleShape::sphere(path_.position(t), radius_); }

  double radius() const { return radius_; }
  const Vec3& center() const { return center_; }
  const Vec3& velocity() const { return velocity_; }
  const geometry::ScriptedPath& path() const { return path_; }

 private:
  double radius_;
  geometry::ScriptedPath path_;
  Vec3 center_ = Vec3::Zero();    // at the last moveTo (m)
  Vec3 velocity_ = Vec3::Zero();  // m/s
};

}  // namespace filum::collision
