// Obstacle: the collision side of what threads touch but do not move — planes, spheres,
// capsules, triangle-mesh organs, implicit (convolution) surfaces — and of scripted tools (the
// probe). Its one query is the signed distance of a point to its surface with the closest
// surface point, the outward normal and the velocity of the surface there; a thread sphere of
// radius r at centre x is in contact when distance(x) < r (paper §3: penalty response to sphere
// contacts; [Lenoir talk 2008]: collision against f(x) = 0, response along ∇f).
#pragma once

#include <optional>

#include "filum/core/collision_pipeline.hpp"
#include "filum/collision/obstacle_shape.hpp"
#include "filum/core/params.hpp"

namespace filum {
class CurveBody;
}

namespace filum::collision {

struct SurfaceSample {
  double distance = 0.0;        // signed distance of the query point to the surface (m), < 0 inside
  Vec3 point = Vec3::Zero();    // closest surface point (m)
  Vec3 normal = Vec3::UnitZ();  // outward unit normal there (from the obstacle towards the outside)
  Vec3 velocity = Vec3::Zero(); // velocity of that surface point (m/s)
};

class Obstacle : public CollisionModel {
 public:
  /// Moves the obstacle to time t (s): scripted obstacles follow their path; others do nothing.
  virtual void moveTo(double /*t*/) {}

  /// Fills `out` and returns true if x is inside or less than max_distance (m) outside;
  /// returns false (out unspecified) when x is farther (no contact possible).
  virtual bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const = 0;

  /// Largest speed of the surface at the current time (m/s), for the margins of continuous
  /// detection; 0 for fixed obstacles.
  virtual double speed() const { return 0.0; }

  /// What the obstacle looks like now (after the last moveTo), for the pictures; kNone: nothing
  /// to draw from here.
  virtual ObstacleShape shape() const { return {}; }
  /// What it looks like at time t, without moving it (a frame drawn at a state's time, after a
  /// restore): a scripted obstacle's shape on its path; the others' current one.
  virtual ObstacleShape shapeAt(double /*t*/) const { return shape(); }

  /// Whether the curve `body` passes through the obstacle at abscissa s, so that its sphere there
  /// makes no contact with it: a thread in the holes a needle made in a wound's lips
  /// (haptics/wound_pad.hpp). No by default.
  virtual bool passesThrough(const CurveBody& /*body*/, double /*s*/) const { return false; }

  /// Coulomb friction coefficient μ of thread contacts on this obstacle ("friction" in the scene
  /// file); nullopt: the pipeline's.
  const std::optional<double>& friction() const { return friction_; }
  void setFriction(std::optional<double> mu) { friction_ = mu; }

 protected:
  /// Reads the parameters every obstacle has ("friction": μ >= 0).
  void readCommon(const Params& p) {
    if (p.has("friction")) friction_ = p.nonNegative({"friction", "1"}, 0.0);
  }

 private:
  std::optional<double> friction_;
};

}  // namespace filum::collision
